// The table of output formats (render/video/output_formats.hpp): one row per OutputKind, rows that agree
// with themselves, the option checks and help texts read from them, and docs/cli.md's table of formats
// printed from them.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <string>

#include "cli_support.hpp"
#include "render/video/output_formats.hpp"

using namespace particles::render;
using particles::test::Result;
using particles::test::Scratch;

namespace {

constexpr OutputKind kKinds[] = {OutputKind::mp4, OutputKind::webm, OutputKind::gif, OutputKind::png,
                                 OutputKind::pngSequence};

bool refuses(const OutputFormat& format, const FormatOptions& options, const std::string& option) {
  try {
    checkFormatOptions(format, "out", options);
  } catch (const std::invalid_argument& e) {
    CHECK_MESSAGE(std::string(e.what()).starts_with(option), e.what());
    return true;
  }
  return false;
}

}  // namespace

TEST_CASE("every output kind has one row, named by a path of its own") {
  CHECK(outputFormats().size() == std::size(kKinds));
  std::set<std::string_view> extensions, examples, names;
  for (const OutputKind kind : kKinds) {
    const OutputFormat& format = outputFormat(kind);
    CAPTURE(format.name);
    CHECK(format.kind == kind);
    CHECK(extensions.insert(format.extension).second);
    CHECK(examples.insert(format.example).second);
    CHECK(names.insert(format.name).second);
    CHECK(format.example.ends_with(format.extension));
    // The path -o gives, in any case, names the row back.
    CHECK(outputFormatOf(std::string(format.example)).kind == kind);
    std::string upper(format.example);
    for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
    CHECK(outputFormatOf(upper).kind == kind);
  }
}

TEST_CASE("an output format's row agrees with itself: crf default in range, fps cap, --at, its writer") {
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    if (format.crf) {
      CHECK(format.crf->lowest <= format.crf->byDefault);
      CHECK(format.crf->byDefault <= format.crf->highest);
      CHECK(crfOf(format, std::nullopt) == format.crf->byDefault);
    }
    if (format.fpsCap) {
      CHECK(1 <= format.fpsCap->byDefault);
      CHECK(format.fpsCap->byDefault <= format.fpsCap->most);
      CHECK_FALSE(format.fpsCap->why.empty());
      CHECK(defaultFps(format, 1000) == format.fpsCap->byDefault);
    }
    CHECK(defaultFps(format, 24) == 24);
    // A run of frames has a writer; the one frame at --at is written by writePng.
    CHECK((format.open == nullptr) == format.oneFrameAt);
    CHECK_FALSE(format.alphaNote.empty());
    // One frame is not split into ranges.
    CHECK_FALSE((format.oneFrameAt && format.splits));
  }
  // The encoders' defaults the goldens, README and bench/README were measured with.
  CHECK(outputFormat(OutputKind::mp4).crf->byDefault == 18);
  CHECK(outputFormat(OutputKind::webm).crf->byDefault == 31);
  CHECK(outputFormat(OutputKind::gif).fpsCap->most == 50);
  CHECK(outputFormat(OutputKind::gif).fpsCap->byDefault == 30);
}

TEST_CASE("the option checks refuse what a format's row does not take, naming the option") {
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    const std::optional<double> at = format.oneFrameAt ? std::optional<double>(0.5) : std::nullopt;
    CHECK_FALSE(refuses(format, {.fps = 24, .at = at}, ""));
    CHECK(refuses(format, {.transparentBackground = true, .at = at}, "--background") != format.keepsAlpha);
    CHECK(refuses(format, {.at = at, .frames = true}, "--frames") != format.splits);
    // --hud goes on every format, but never over a transparent background (its panel is opaque).
    CHECK_FALSE(refuses(format, {.hud = true, .at = at}, ""));
    if (format.keepsAlpha) CHECK(refuses(format, {.transparentBackground = true, .hud = true, .at = at}, "--hud"));
    CHECK(refuses(format, {.crf = 0, .at = at}, "--crf") != format.crf.has_value());
    if (format.crf) {
      CHECK_FALSE(refuses(format, {.crf = format.crf->highest, .at = at}, ""));
      CHECK(refuses(format, {.crf = format.crf->highest + 1, .at = at}, "--crf"));
      CHECK(refuses(format, {.crf = format.crf->lowest - 1, .at = at}, "--crf"));
      CHECK_THROWS_AS(crfOf(format, format.crf->highest + 1), std::invalid_argument);
      CHECK(crfOf(format, format.crf->lowest) == format.crf->lowest);
    } else {
      CHECK_THROWS_AS(crfOf(format, std::nullopt), std::logic_error);
    }
    if (format.fpsCap) {
      CHECK_FALSE(refuses(format, {.fps = format.fpsCap->most}, ""));
      CHECK(refuses(format, {.fps = format.fpsCap->most + 1}, "--fps"));
    }
    // --at: required by the one-frame format, refused by every other.
    CHECK(refuses(format, {}, format.oneFrameAt ? "-o" : "") == format.oneFrameAt);
    CHECK(refuses(format, {.at = 0.5}, "--at") != format.oneFrameAt);
  }
}

TEST_CASE("render's help texts list every format with its numbers, from the table") {
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    CHECK(outputHelp().find(format.example) != std::string::npos);
    CHECK((atHelp().find(format.example) != std::string::npos) == format.oneFrameAt);
    if (format.crf) {
      const std::string crf = fmt::format("{} ({}) {} … {}, default {}", format.name, format.codec, format.crf->lowest,
                                          format.crf->highest, format.crf->byDefault);
      CHECK_MESSAGE(crfHelp().find(crf) != std::string::npos, crfHelp());
    }
    if (format.fpsCap) {
      const std::string cap = fmt::format("{} at most {} unless given, at most {}", format.name,
                                          format.fpsCap->byDefault, format.fpsCap->most);
      CHECK_MESSAGE(fpsHelp().find(cap) != std::string::npos, fpsHelp());
    }
  }
  // Names are listed whole ("PNG sequence" holds "PNG"): only the rows that keep alpha or split.
  CHECK(backgroundHelp().ends_with(": WebM, PNG sequence and PNG only)"));
  CHECK(framesHelp().find("for MP4 and PNG sequence output") != std::string::npos);
  CHECK(crfHelp().find("GIF") == std::string::npos);

  // The program shows them.
  Scratch s;
  const Result r = s.run("render --help");
  REQUIRE(r.code == 0);
  for (const std::string& help : {outputHelp(), atHelp(), framesHelp(), fpsHelp(), backgroundHelp(), crfHelp()}) {
    CHECK_MESSAGE(r.out.find(help) != std::string::npos, help);
  }
}

TEST_CASE("docs/cli.md holds the table of output formats as the rows print it") {
  std::ifstream in(std::filesystem::path(PARTICLES_SOURCE_DIR) / "docs/cli.md", std::ios::binary);
  REQUIRE(in);
  const std::string page{std::istreambuf_iterator<char>(in), {}};
  // On failure: paste this table into docs/cli.md's "Videos for the web".
  CHECK_MESSAGE(page.find(outputFormatsMarkdown()) != std::string::npos, "\n" << outputFormatsMarkdown());
}

TEST_CASE("a format whose chroma is halved refuses odd sides, naming the next even size, and the others take any") {
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    CHECK_NOTHROW(checkFrameSize(format, 4, 6, false));
    for (const auto& [width, height] : {std::pair{3, 6}, std::pair{4, 5}, std::pair{1, 1}, std::pair{0, 4}}) {
      CAPTURE(width);
      CAPTURE(height);
      if (format.halvedChroma.empty()) {
        CHECK_NOTHROW(checkFrameSize(format, width, height, format.keepsAlpha));
        continue;
      }
      try {
        checkFrameSize(format, width, height, false);
        FAIL_CHECK("accepted");
      } catch (const std::invalid_argument& e) {
        const std::string even = std::to_string(width + width % 2) + "x" + std::to_string(height + height % 2);
        CHECK(std::string(e.what()) == std::string(format.name) + " (" + std::string(format.codec) + ", " +
                                           std::string(format.halvedChroma) + ") needs an even width and height; " +
                                           std::to_string(width) + "x" + std::to_string(height) + " is not (try " +
                                           even + ", or write PNG frames)");
      }
    }
  }
  // With alpha kept, the message names the pixel format that holds it.
  try {
    checkFrameSize(outputFormat(OutputKind::webm), 3, 3, true);
    FAIL_CHECK("accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).starts_with("WebM (VP9, yuva420p) needs an even width and height; 3x3 is not"));
  }
  CHECK(frameSizeHelp() ==
        "Odd sizes are refused for MP4 and WebM (yuv420p needs even sizes); GIF, PNG sequence and PNG take any size.");
}

TEST_CASE("concat joins the formats whose row says so, whatever the extension's case") {
  CHECK_NOTHROW(checkConcatOutput("joined.mp4"));
  CHECK_NOTHROW(checkConcatOutput("JOINED.MP4"));
  for (const char* path : {"joined.webm", "joined.gif", "frames/", "joined.png", "joined"}) {
    CAPTURE(path);
    try {
      checkConcatOutput(path);
      FAIL_CHECK("accepted");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()) == "-o " + std::string(path) + ": the joined video must be a .mp4 file");
    }
  }
  CHECK(concatOutputHelp() == "The joined video (.mp4)");
}
