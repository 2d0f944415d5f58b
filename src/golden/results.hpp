#pragma once
// What a `particles golden check` run found (golden/README.md): one result per frame and per state
// of the manifest, and the facts of the run. The report folder holds them three ways, written and
// read here (src/golden/report_*.cpp):
//   report.html   for people: failures first, expected / actual / diff with a slider and a blink
//                 comparison, the numbers, the commands that reproduce each failure; readable
//                 with JavaScript off;
//   junit.xml     for CI test views (GitHub, GitLab, Jenkins): one testcase per frame and state;
//   results.json  for scripts, and what `golden report` merges and `golden update --from` accepts.
// Pictures and state files sit beside them, linked by paths relative to the folder, so the folder
// is whole on its own.

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include <particles/choices.hpp>

namespace particles::golden {

// passed: matches (or, for an `expect: differ` control, differs); failed: it does not; missing: no
// reference yet (`golden update --missing` creates it); error: it could not be checked (the
// scenario did not load, the simulation blew up, the reference is unreadable).
// Outcome: include/particles/choices.hpp, the library's and this room's one type.
std::string_view outcomeName(Outcome outcome);  // "passed", "failed", "missing", "error"
std::optional<Outcome> outcomeFromName(std::string_view name);

// The numbers of one frame comparison, as `particles compare` prints them.
struct FrameNumbers {
  int threshold = 0;                      // per channel, 0 … 255
  double maxShare = 0.0;                  // 0 … 1
  long differing = 0;                     // pixels with a channel difference > threshold
  long pixels = 0;                        // width × height
  double share = 0.0;                     // differing / pixels
  int largest = 0;                        // largest channel difference, 0 … 255
  std::optional<std::array<int, 4>> box;  // x0, y0, x1, y1 of the differing pixels, inclusive; none: none differ
  int width = 0, height = 0;
};

// Files of a result, relative to the report folder (empty: not kept). A passing frame keeps none;
// a failing or missing one keeps what it has (a missing reference has no expected or diff); a
// control (`expect: differ`) that passes keeps its actual frame and diff, which show what the
// comparison saw.
struct KeptFiles {
  std::string actual, expected, diff;
};

struct FrameResult {
  std::string name;           // the frame's name in the manifest (cloth_t2.5)
  std::string scenario;       // as the manifest writes it
  std::string time;           // seconds, as the manifest writes it
  bool expectDiffer = false;  // a control
  Outcome outcome = Outcome::error;
  std::string message;                  // one line for a failure, missing reference or error; empty when passed
  std::optional<FrameNumbers> numbers;  // when it was compared
  KeptFiles files;
  std::string reference;               // the reference's path as the manifest resolves it, relative to where check ran
  std::vector<std::string> reproduce;  // shell commands that reproduce the result, quoted for a POSIX shell
  double seconds = 0.0;                // wall time of its share of the run (render, read, compare)
};

// The first value of a state check beyond its tolerance (in time order, then point order, then
// quantity order x, y, vx, vy, angle, omega), or the largest deviation when none is.
struct StateDeviation {
  std::string time;      // as the manifest writes it
  std::string point;     // as the trace names it: bob, cloth[3][4], #7, link0
  std::string quantity;  // x, y, vx, vy, angle, omega
  double expected = 0.0, actual = 0.0, difference = 0.0, tolerance = 0.0;
};

struct StateResult {
  std::string name;
  std::string scenario;
  std::vector<std::string> times;  // as the manifest writes them
  Outcome outcome = Outcome::error;
  std::string message;
  std::optional<StateDeviation> firstBeyond;  // failed: the first value beyond its tolerance
  std::optional<StateDeviation> largest;      // compared: the largest |difference| / tolerance
  long values = 0;                            // values compared
  KeptFiles files;                            // actual.csv and expected.csv (no diff)
  std::string reference;
  std::vector<std::string> reproduce;
  double seconds = 0.0;
};

// How the run was made: what a frame's pixels depend on beyond the manifest.
struct RunFacts {
  std::string manifest;      // as given on the command line
  std::string program;       // `particles 0.x.y`
  std::string gl;            // the backend, device and GL renderer that drew the frames, or empty
  std::string lpNumThreads;  // LP_NUM_THREADS, when set
  std::string overrides;     // command-line settings over the manifest's (--raster tiles --max-share 0.0005), or empty
  std::string shard;         // "2/3", or empty for the whole manifest
  double seconds = 0.0;      // wall time of the run
};

struct GoldenResults {
  std::vector<RunFacts> runs;  // one per run merged into these results (one for a plain check)
  std::vector<FrameResult> frames;
  std::vector<StateResult> states;

  struct Counts {
    long passed = 0, failed = 0, missing = 0, error = 0;
    long total() const { return passed + failed + missing + error; }
  };
  Counts counts() const;
  bool allPassed() const {
    const Counts c = counts();
    return c.total() == c.passed;
  }
};

// The file names in a report folder.
inline constexpr std::string_view kReportHtml = "report.html";
inline constexpr std::string_view kJunitXml = "junit.xml";
inline constexpr std::string_view kResultsJson = "results.json";

// Writes report.html, junit.xml and results.json into `folder` (which exists and already holds
// the kept files), each under a temporary name renamed when complete. Throws OutputError.
void writeReport(const std::filesystem::path& folder, const GoldenResults& results);

// The results.json of a report folder, checked: a file that is not one (bad JSON, nested too deep,
// unknown outcome, a kept file's path that leaves the folder or is absolute) throws
// std::invalid_argument naming the file and what is wrong; at most maxInputMiB are read.
GoldenResults readResults(const std::filesystem::path& folder, std::uintmax_t maxInputMiB);

// What a report folder consists of: its three pages and every kept file its results list
// (paths relative to the folder, with '/').
std::set<std::string> reportFiles(const GoldenResults& results);

// The same checks of results.json's text in memory (`file` names it in messages; the fuzzer's
// entry point), but those that need the folder: a kept file's path must still be relative and
// free of "..", but whether it leads out through a symbolic link is readResults' to check. Also
// refused: arrays and objects nested more than report::kMaxResultsDepth deep (results_json.hpp).
// Every message quotes at most about 80 bytes of a value from the text.
GoldenResults parseResultsJson(std::string_view text, const std::string& file);

// The one-line summary `golden check` prints: "golden: 17 frames, 3 states: 18 passed, 1 failed,
// 1 missing (report: DIR/report.html)".
std::string summaryLine(const GoldenResults& results, const std::filesystem::path& folder);

}  // namespace particles::golden
