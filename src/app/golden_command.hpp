#pragma once
// `particles golden`: golden tests of anyone's scenarios (golden/README.md).
//   golden check [MANIFEST] [-o DIR] [--jobs N] [--shard K/N] [--only NAME…] [--gl …]
//       renders and simulates the manifest's frames and states, compares them with their
//       references and writes DIR/report.html, junit.xml and results.json.
//       Exit 0 every check passed; 1 one failed or has no reference yet; 2 a bad manifest, usage or
//       an unusable reference (the report is still written); 3 the report could not be written.
//   golden update [MANIFEST] [NAME…] [--missing] [--from DIR…]
//       writes references: rendered, or accepted from report folders (--from) without rendering.
//   golden report DIR… -o DIR
//       merges the report folders of shards (`check --shard K/N`) into one.
// The work is the golden room's (src/golden/); this file holds the command line.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "app/command.hpp"
#include "input/text_file.hpp"

namespace particles::app {

// The manifest `golden check` and `golden update` read when none is given.
inline constexpr const char* kDefaultGoldenManifest = "golden/golden.yaml";
inline constexpr const char* kDefaultGoldenReport = "golden-report";

struct GoldenRunOptions {
  std::string manifest = kDefaultGoldenManifest;
  int jobs = 0;  // 0: half the machine's cores, at least 1
  std::string gl;
  bool gpu = false;  // draw on a GPU through EGL (render's --gpu)
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;
  bool quiet = false;
};

struct GoldenCheckOptions {
  GoldenRunOptions run;
  std::string output = kDefaultGoldenReport;
  std::string shard;  // K/N
  std::vector<std::string> only;
  std::string raster;
  std::optional<int> threshold;
  std::optional<double> maxShare;
};

struct GoldenUpdateOptions {
  GoldenRunOptions run;
  std::vector<std::string> names;
  std::vector<std::string> from;
  bool missing = false;
};

struct GoldenReportOptions {
  std::vector<std::string> folders;
  std::string output = kDefaultGoldenReport;
  std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB;
  bool quiet = false;
};

struct GoldenOptions {
  GoldenCheckOptions check;
  GoldenUpdateOptions update;
  GoldenReportOptions report;
  // Which of the three the command line named (set by CLI11 when parsed).
  CLI::App* checkCommand = nullptr;
  CLI::App* updateCommand = nullptr;
  CLI::App* reportCommand = nullptr;
};

extern const CommandDescriptor<GoldenOptions> kGoldenCommand;

}  // namespace particles::app
