// `particles compare`: see compare_command.hpp.
#include "app/compare_command.hpp"

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <new>
#include <stdexcept>

#include "app/exit_codes.hpp"
#include "render/errors.hpp"
#include "render/image_compare.hpp"
#include "render/png_io.hpp"
#include "render/render_options.hpp"

namespace particles::app {

namespace {

void addCompareOptions(CLI::App& command, CompareOptions& o) {
  command.add_option("expected", o.expected, "The reference frame (PNG), e.g. golden/cloth_t2.5.png")->required();
  command.add_option("actual", o.actual, "The frame to check (PNG), of the same size")->required();
  command.add_option("--diff", o.diff,
                     "Write a PNG of the differences: magenta above the threshold, teal below it, the bounding box in "
                     "yellow, over a dimmed grey copy of the expected frame");
  command
      .add_option("--threshold", o.threshold, "A pixel differs when any channel (0 … 255) differs by more than this")
      ->check(CLI::Range(0, 255))
      ->capture_default_str();
  command
      .add_option("--max-share", o.maxShare,
                  fmt::format("Fail when more than this share (0 … 1) of the pixels differ; {} = {} %",
                              render::kDefaultMaxShare, 100 * render::kDefaultMaxShare))
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  command.add_flag("-q,--quiet", o.quiet, "Print nothing when the frames match");
  // Two frames of the largest size, 4 bytes a pixel each.
  const std::uint64_t largestPairGiB = 2 * 4 * std::uint64_t(render::kMaxImageSide) * render::kMaxImageSide >> 30;
  command.footer(fmt::format(
      "Exit codes: 0 the frames match, 1 they differ, 2 bad input (unreadable PNG, sizes differ: read from\n"
      "the headers, nothing decoded; a --diff that is not .png or is one of the frames), 3 the --diff picture\n"
      "could not be written or memory ran out (two {0}x{0} frames decode to {1} GiB). Defaults and how they\n"
      "were measured: golden/README.md.\n"
      "Examples:\n"
      "  particles compare golden/cloth_t2.5.png cloth.png\n"
      "  particles compare golden/cloth_t2.5.png cloth.png --diff cloth_diff.png --threshold 16 --max-share 0.01\n",
      render::kMaxImageSide, largestPairGiB));
}

int compareCommand(const CompareOptions& o) {
  std::string diffExtension = std::filesystem::path(o.diff).extension().string();
  std::transform(diffExtension.begin(), diffExtension.end(), diffExtension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (!o.diff.empty() && diffExtension != ".png") {
    throw InputError(fmt::format("--diff {}: the picture of the differences is a PNG; name it .png", o.diff));
  }
  // The sizes come from the two headers, before either frame is decoded: frames of different sizes
  // are told apart without their pixels (a 16384² PNG decodes to 1 GiB).
  render::Image expected, actual;
  try {
    const render::PngSize e = render::readPngSize(o.expected);
    const render::PngSize a = render::readPngSize(o.actual);
    const std::string mismatch = render::sizeMismatch(e.width, e.height, a.width, a.height);
    if (!mismatch.empty()) throw InputError(fmt::format("{} and {}: {}", o.expected, o.actual, mismatch));
    expected = render::readPng(o.expected);
    actual = render::readPng(o.actual);
  } catch (const render::OutputError& e) {  // here an input that cannot be read: bad input
    throw InputError(e.what());
  }
  // A file changed between its header and its pixels still has its size checked.
  const std::string mismatch = render::sizeMismatch(expected, actual);
  if (!mismatch.empty()) throw InputError(fmt::format("{} and {}: {}", o.expected, o.actual, mismatch));
  render::ImageComparison c;
  try {
    c = render::compareImages(expected, actual, {o.threshold, o.maxShare});
  } catch (const std::invalid_argument& e) {
    throw InputError(e.what());
  }

  if (!o.quiet || !c.passed) {
    fmt::print("{} vs {} ({}×{})\n", o.expected, o.actual, c.width, c.height);
    fmt::print("  share:   {:.4f} % of the pixels differ by more than {} ({} of {}; bound {:.4g} %)\n", 100.0 * c.share,
               o.threshold, c.differing, c.pixels, 100.0 * o.maxShare);
    fmt::print("  largest: {} (of 255, any channel)\n", c.largestDifference);
    if (c.box) {
      fmt::print("  box:     x {}…{}, y {}…{} ({}×{} px, from the top left)\n", c.box->x0, c.box->x1, c.box->y0,
                 c.box->y1, c.box->width(), c.box->height());
    } else {
      fmt::print("  box:     none\n");
    }
  }
  if (!o.diff.empty()) {
    try {
      render::writePng(o.diff, render::diffImage(expected, actual, o.threshold));  // appears only when complete
    } catch (const render::OutputError& e) {
      throw render::OutputError(std::string("--diff: ") + e.what());
    } catch (const std::bad_alloc&) {
      throw render::OutOfMemory(fmt::format("--diff {}: the {}×{} picture of the differences needs {} MiB more", o.diff,
                                            c.width, c.height, (std::size_t(c.width) * c.height * 4) >> 20));
    }
    if (!o.quiet || !c.passed) fmt::print("  diff:    {}\n", o.diff);
  }
  if (!c.passed) {
    fmt::print("DIFFERENT: more than {:.4g} % of the pixels differ\n", 100.0 * o.maxShare);
    return kSimulationFailed;  // exit 1: the result is wrong
  }
  if (!o.quiet) fmt::print("ok\n");
  return kOk;
}

CommandFiles compareFiles(const CompareOptions& o) {
  return {{{"--diff", o.diff}}, {{"the expected frame", o.expected}, {"the actual frame", o.actual}}};
}

}  // namespace

const CommandDescriptor<CompareOptions> kCompareCommand = {
    .name = "compare",
    .summary = "Compare a frame with its golden frame: exit 0 if they match, 1 if they differ (docs/physics.md §10)",
    .addOptions = addCompareOptions,
    .run = compareCommand,
    .files = compareFiles,
};

}  // namespace particles::app
