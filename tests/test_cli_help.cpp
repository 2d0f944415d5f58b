// The numbers that `particles COMMAND --help` states are the code's: a help text once
// said tiles were drawn from 5000 shapes when the renderer switched at 20000. Each number is read
// back from the help of a freshly built command line and compared with the constant it stands for.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "app/cli.hpp"
#include "app/command_table.hpp"
#include "app/stability_command.hpp"
#include "core/stability.hpp"
#include "input/text_file.hpp"
#include "plot/figure.hpp"
#include "render/video/frame_writer.hpp"
#include "render/image_compare.hpp"
#include "render/video/output_formats.hpp"
#include "render/png_io.hpp"
#include "render/render_options.hpp"

namespace {

std::string helpOf(const std::string& command) {
  particles::app::Cli cli;
  return cli.app.get_subcommand(command)->help();
}

// The groups of the first match of `pattern` in `help`; fails the test when there is none.
std::vector<std::string> numbersAt(const std::string& help, const std::string& pattern) {
  std::smatch m;
  const bool found = std::regex_search(help, m, std::regex(pattern));
  CHECK_MESSAGE(found, "no match for " << pattern << " in\n" << help);
  std::vector<std::string> groups;
  if (found) {
    for (size_t i = 1; i < m.size(); ++i) groups.push_back(m[i].str());
  }
  return groups;
}

// The one number `pattern` captures, read as a double (NaN when it does not match).
double numberAt(const std::string& help, const std::string& pattern) {
  const auto groups = numbersAt(help, pattern);
  return groups.size() == 1 ? std::stod(groups[0]) : std::nan("");
}

}  // namespace

TEST_CASE("cli help: every command that reads files states the default --max-input") {
  // What reads no text file: compare reads PNGs, concat MP4 segments (through libav), schema nothing.
  const std::set<std::string> readNoText = {"compare", "concat", "schema"};
  size_t checked = 0;
  for (const particles::app::AddCommand add : particles::app::kCommands) {
    CLI::App program;
    const auto bound = add(program);  // holds the options the command's are bound to
    const std::string name(bound->name());
    CLI::App* command = program.get_subcommand(name);
    // A command of subcommands (golden: check, update, report) has its options on each of them.
    std::vector<CLI::App*> leaves = command->get_subcommands({});
    if (leaves.empty()) leaves = {command};
    for (CLI::App* leaf : leaves) {
      const std::string path = leaf == command ? name : name + " " + leaf->get_name();
      CAPTURE(path);
      if (readNoText.count(name) > 0) {
        CHECK(leaf->get_option_no_throw("--max-input") == nullptr);
        continue;
      }
      CHECK(numberAt(leaf->help(), R"(--max-input UINT:UINT in \[1 - \d+\]=(\d+))") ==
            double(particles::input::kDefaultMaxInputMiB));
      ++checked;
    }
  }
  CHECK(checked == particles::app::kCommands.size() - readNoText.size() + 2);  // golden's three, not one
}

TEST_CASE("cli help: render states the renderer's and the encoders' numbers") {
  using namespace particles::render;
  const std::string help = helpOf("render");
  CHECK(numberAt(help, R"(auto \(with --gpu resident, and tiles from (\d+) shapes)") == double(kTilesFromShapes));

  const auto keyint = numbersAt(help, R"(--keyint FLOAT:FLOAT in \[([\d.]+) - ([\d.]+)\]=([\d.]+))");
  REQUIRE(keyint.size() == 3);
  CHECK(std::stod(keyint[1]) == kMaxKeyintSeconds);
  CHECK(std::stod(keyint[2]) == VideoOptions{}.keyintSeconds);

  // --msaa's allowed values, its default and the list in its text.
  const auto msaa = numbersAt(help, R"(--msaa INT:\{([\d,]+)\}=(\d+) +Anti-aliasing samples per pixel: ([^\n]+))");
  REQUIRE(msaa.size() == 3);
  std::vector<std::string> counts;
  for (int n : kSampleCounts) counts.push_back(std::to_string(n));
  CHECK(msaa[0] == fmt::format("{}", fmt::join(counts, ",")));
  CHECK(std::stoi(msaa[1]) == RenderOptions{}.msaa);
  std::vector<std::string> listed;
  const std::regex number(R"(\d+)");
  for (auto it = std::sregex_iterator(msaa[2].begin(), msaa[2].end(), number); it != std::sregex_iterator(); ++it) {
    listed.push_back(it->str());
  }
  CHECK(listed == counts);

  // The formats' numbers (render/video/output_formats.hpp): each crf range and default, each fps cap, in
  // the option's help and, for the GIF, the footer.
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    if (format.crf) {
      const auto crf =
          numbersAt(help, fmt::format(R"(--crf INT [^\n]*{} \([^)]*\) (\d+) … (\d+), default (\d+))", format.name));
      REQUIRE(crf.size() == 3);
      CHECK(std::stoi(crf[0]) == format.crf->lowest);
      CHECK(std::stoi(crf[1]) == format.crf->highest);
      CHECK(std::stoi(crf[2]) == format.crf->byDefault);
    }
    if (format.fpsCap) {
      const auto fps = numbersAt(
          help, fmt::format(R"(--fps FLOAT [^\n]*{} at most (\d+) unless given, at most (\d+))", format.name));
      REQUIRE(fps.size() == 2);
      CHECK(std::stoi(fps[0]) == format.fpsCap->byDefault);
      CHECK(std::stoi(fps[1]) == format.fpsCap->most);
    }
  }
  const FpsCap& gifCap = *outputFormat(OutputKind::gif).fpsCap;
  const auto footerGifFps = numbersAt(help, R"(at most (\d+) fps \((\d+) unless --fps says\))");
  REQUIRE(footerGifFps.size() == 2);
  CHECK(std::stoi(footerGifFps[0]) == gifCap.most);
  CHECK(std::stoi(footerGifFps[1]) == gifCap.byDefault);

  CHECK(numberAt(help, R"(--png-level INT=(\d+))") == PngOptions{}.compressionLevel);
  CHECK(numbersAt(help, R"(--preset TEXT=(\w+))") == std::vector<std::string>{VideoOptions{}.preset});
}

TEST_CASE("cli help: stability states the study's defaults") {
  using namespace particles;
  const std::string help = helpOf("stability");
  CHECK(numberAt(help, R"(--energy-tolerance FLOAT=([\d.e+-]+))") == StabilityCriteria{}.energyTolerance);
  CHECK(numberAt(help, R"(--stretch-factor FLOAT=([\d.e+-]+))") == StabilityOptions{}.stretchFactor);
  CHECK(numberAt(help, R"(--shake-threshold FLOAT=([\d.e+-]+))") == StabilityCriteria{}.shakeThreshold);
  CHECK(numberAt(help, R"(--max-dt FLOAT=([\d.e+-]+))") == StabilityOptions{}.maxDt);
  CHECK(numberAt(help, R"(the scenario's dt / (\d+)\))") == app::kMinDtDivisor);
  CHECK(numberAt(help, R"(halved up to (\d+) times)") == app::kReferenceHalvings);
}

TEST_CASE("cli help: plot and compare state the figure's and the comparison's defaults") {
  using namespace particles;
  const std::string plotHelp = helpOf("plot");
  CHECK(numberAt(plotHelp, R"(Width in px \(default (\d+)\))") == plot::Figure{}.widthPx);
  CHECK(numberAt(plotHelp, R"(Height in px \(default (\d+)\))") == plot::Figure{}.heightPx);

  const std::string help = helpOf("compare");
  CHECK(numberAt(help, R"(--threshold INT:INT in \[0 - 255\]=(\d+))") == render::kDefaultThreshold);
  CHECK(numberAt(help, R"(--max-share FLOAT:FLOAT in \[0 - 1\]=([\d.e+-]+))") == render::kDefaultMaxShare);
  const auto share = numbersAt(help, R"(pixels differ; ([\d.]+) = ([\d.]+) %)");
  REQUIRE(share.size() == 2);
  CHECK(std::stod(share[0]) == render::kDefaultMaxShare);
  CHECK(std::stod(share[1]) == doctest::Approx(100 * render::kDefaultMaxShare));
  const auto largest = numbersAt(help, R"(two (\d+)x(\d+) frames decode to (\d+) GiB)");
  REQUIRE(largest.size() == 3);
  CHECK(std::stoi(largest[0]) == render::kMaxImageSide);
  CHECK(std::stoi(largest[1]) == render::kMaxImageSide);
  CHECK(std::stod(largest[2]) == 2.0 * 4.0 * render::kMaxImageSide * render::kMaxImageSide / (1 << 30));
}
