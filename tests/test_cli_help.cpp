// The numbers that `particles COMMAND --help` states are the code's: a help text once
// said tiles were drawn from 5000 shapes when the renderer switched at 20000. Each number is read
// back from the help of a freshly built command line and compared with the constant it stands for.
#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>
#include <sstream>
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
  return cli.command(command).help();
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

// One option's entry in a help text, read by meaning rather than by one CLI11's layout: 2.1 … 2.3
// write "--msaa INT:{1,2,4,8,16}=4   Anti-aliasing …", 2.4 "--msaa INT:{1,2,4,8,16} [4] " with the
// description on the next line when the names, type and default are wider than their column.
struct OptionHelp {
  bool found = false;
  std::string type;       // "INT"
  std::string check;      // "{1,2,4,8,16}" (allowed values), "UINT in [1 - 1048576]" (a range), or ""
  std::string byDefault;  // what the help states as the default, or "" when it states none
  std::string text;       // the description, its lines joined by a space
  // A range check's ends ("1", "1048576"); empty when the check is no range.
  std::vector<std::string> range() const {
    std::smatch m;
    if (!std::regex_match(check, m, std::regex(R"(\w+ in \[(\S+) - (\S+)\])"))) return {};
    return {m[1].str(), m[2].str()};
  }
};

// The entry of the option called `name` ("--msaa"; "-o,--output" lists two names) in `help`; fails
// the test when there is none. An entry's line starts with its names after 2 spaces; its
// description's further lines are indented past them (CLI11's column 30).
OptionHelp optionHelp(const std::string& help, const std::string& name) {
  std::istringstream lines(help);
  std::string line;
  OptionHelp entry;
  const auto trimmed = [](const std::string& t) {
    const std::size_t a = t.find_first_not_of(' '), b = t.find_last_not_of(' ');
    return a == std::string::npos ? std::string() : t.substr(a, b - a + 1);
  };
  while (std::getline(lines, line)) {
    const std::size_t start = line.find_first_not_of(' ');
    if (entry.found) {
      if (start == std::string::npos || start < 4) break;
      entry.text += (entry.text.empty() ? "" : " ") + trimmed(line);
      continue;
    }
    if (start == std::string::npos || line[start] != '-') continue;
    const std::size_t namesEnd = std::min(line.find(' ', start), line.size());
    std::istringstream names(line.substr(start, namesEnd - start));
    bool named = false;
    for (std::string one; std::getline(names, one, ',');) named = named || one == name;
    if (!named) continue;
    entry.found = true;
    // The type, check and default end where 2 spaces (or the line) do; the description follows.
    const std::string rest = namesEnd < line.size() ? line.substr(namesEnd + 1) : "";
    const std::size_t gap = std::min(rest.find("  "), rest.size());
    entry.text = trimmed(rest.substr(gap));
    std::smatch m;
    const std::string signature = rest.substr(0, gap);
    if (std::regex_search(signature, m,
                          std::regex(R"(^(\w+)(?::(\{[^}]*\}|\w+ in \[[^\]]*\]))?(?:=(\S+)| \[([^\]]*)\])?)"))) {
      entry.type = m[1].str();
      entry.check = m[2].str();
      entry.byDefault = m[3].matched ? m[3].str() : m[4].str();
    }
  }
  CHECK_MESSAGE(entry.found, "no option " << name << " in\n" << help);
  return entry;
}

// The default `name`'s entry states, read as a double (NaN when it states none).
double defaultOf(const std::string& help, const std::string& name) {
  const std::string stated = optionHelp(help, name).byDefault;
  CHECK_MESSAGE(!stated.empty(), name << " states no default in\n" << help);
  return stated.empty() ? std::nan("") : std::stod(stated);
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
    CLI::App* command = &bound->addOptions();
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
      const OptionHelp maxInput = optionHelp(leaf->help(), "--max-input");
      CHECK(maxInput.type == "UINT");
      REQUIRE(maxInput.range().size() == 2);
      CHECK(maxInput.range()[0] == "1");
      CHECK(defaultOf(leaf->help(), "--max-input") == double(particles::input::kDefaultMaxInputMiB));
      ++checked;
    }
  }
  CHECK(checked == particles::app::kCommands.size() - readNoText.size() + 2);  // golden's three, not one
}

TEST_CASE("cli help: render states the renderer's and the encoders' numbers") {
  using namespace particles::render;
  const std::string help = helpOf("render");
  CHECK(numberAt(help, R"(auto \(with --gpu resident, and tiles from (\d+) shapes)") == double(kTilesFromShapes));

  const OptionHelp keyint = optionHelp(help, "--keyint");
  REQUIRE(keyint.range().size() == 2);
  CHECK(std::stod(keyint.range()[1]) == kMaxKeyintSeconds);
  CHECK(defaultOf(help, "--keyint") == VideoOptions{}.keyintSeconds);

  // --msaa's allowed values, its default and the list in its text.
  const OptionHelp msaa = optionHelp(help, "--msaa");
  std::vector<std::string> counts;
  for (int n : kSampleCounts) counts.push_back(std::to_string(n));
  CHECK(msaa.check == fmt::format("{{{}}}", fmt::join(counts, ",")));
  CHECK(defaultOf(help, "--msaa") == RenderOptions{}.msaa);
  const auto listedText = numbersAt(msaa.text, R"(^Anti-aliasing samples per pixel: (.+))");
  REQUIRE(listedText.size() == 1);
  std::vector<std::string> listed;
  const std::regex number(R"(\d+)");
  for (auto it = std::sregex_iterator(listedText[0].begin(), listedText[0].end(), number); it != std::sregex_iterator();
       ++it) {
    listed.push_back(it->str());
  }
  CHECK(listed == counts);

  // The formats' numbers (render/video/output_formats.hpp): each crf range and default, each fps cap, in
  // the option's help and, for the GIF, the footer.
  for (const OutputFormat& format : outputFormats()) {
    CAPTURE(format.name);
    if (format.crf) {
      const auto crf = numbersAt(optionHelp(help, "--crf").text,
                                 fmt::format(R"({} \([^)]*\) (\d+) … (\d+), default (\d+))", format.name));
      REQUIRE(crf.size() == 3);
      CHECK(std::stoi(crf[0]) == format.crf->lowest);
      CHECK(std::stoi(crf[1]) == format.crf->highest);
      CHECK(std::stoi(crf[2]) == format.crf->byDefault);
    }
    if (format.fpsCap) {
      const auto fps = numbersAt(optionHelp(help, "--fps").text,
                                 fmt::format(R"({} at most (\d+) unless given, at most (\d+))", format.name));
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

  CHECK(defaultOf(help, "--png-level") == PngOptions{}.compressionLevel);
  CHECK(optionHelp(help, "--preset").byDefault == VideoOptions{}.preset);
}

TEST_CASE("cli help: stability states the study's defaults") {
  using namespace particles;
  const std::string help = helpOf("stability");
  CHECK(defaultOf(help, "--energy-tolerance") == StabilityCriteria{}.energyTolerance);
  CHECK(defaultOf(help, "--stretch-factor") == StabilityOptions{}.stretchFactor);
  CHECK(defaultOf(help, "--shake-threshold") == StabilityCriteria{}.shakeThreshold);
  CHECK(defaultOf(help, "--max-dt") == StabilityOptions{}.maxDt);
  CHECK(numberAt(help, R"(the scenario's dt / (\d+)\))") == app::kMinDtDivisor);
  CHECK(numberAt(help, R"(halved up to (\d+) times)") == app::kReferenceHalvings);
}

TEST_CASE("cli help: plot and compare state the figure's and the comparison's defaults") {
  using namespace particles;
  const std::string plotHelp = helpOf("plot");
  CHECK(numberAt(plotHelp, R"(Width in px \(default (\d+)\))") == plot::Figure{}.widthPx);
  CHECK(numberAt(plotHelp, R"(Height in px \(default (\d+)\))") == plot::Figure{}.heightPx);

  const std::string help = helpOf("compare");
  const OptionHelp threshold = optionHelp(help, "--threshold");
  CHECK(threshold.range() == std::vector<std::string>{"0", "255"});
  CHECK(defaultOf(help, "--threshold") == render::kDefaultThreshold);
  const OptionHelp maxShare = optionHelp(help, "--max-share");
  CHECK(maxShare.range() == std::vector<std::string>{"0", "1"});
  CHECK(defaultOf(help, "--max-share") == render::kDefaultMaxShare);
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
