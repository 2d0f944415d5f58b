// results.json, written and read: see results_json.hpp.
#include "golden/results_json.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "golden/json_reader.hpp"
#include "golden/report_text.hpp"
#include "input/text_file.hpp"

namespace particles::golden {

namespace {

using OrderedJson = nlohmann::ordered_json;

// ---- writing ----------------------------------------------------------------------------------

OrderedJson jsonText(std::string_view text) {
  return report::validUtf8(text);
}

OrderedJson jsonNumber(double value) {
  if (std::isfinite(value)) return value;
  return report::numberText(value);  // "nan", "inf", "-inf": JSON has no such numbers
}

OrderedJson jsonTexts(const std::vector<std::string>& texts) {
  OrderedJson list = OrderedJson::array();
  for (const std::string& text : texts) list.push_back(jsonText(text));
  return list;
}

OrderedJson jsonFiles(const KeptFiles& files) {
  return {{"actual", jsonText(files.actual)}, {"expected", jsonText(files.expected)}, {"diff", jsonText(files.diff)}};
}

OrderedJson jsonNumbers(const std::optional<FrameNumbers>& n) {
  if (!n) return nullptr;
  OrderedJson box = nullptr;
  if (n->box) box = {(*n->box)[0], (*n->box)[1], (*n->box)[2], (*n->box)[3]};
  return {{"threshold", n->threshold},
          {"max_share", jsonNumber(n->maxShare)},
          {"differing", n->differing},
          {"pixels", n->pixels},
          {"share", jsonNumber(n->share)},
          {"largest", n->largest},
          {"box", box},
          {"width", n->width},
          {"height", n->height}};
}

OrderedJson jsonDeviation(const std::optional<StateDeviation>& d) {
  if (!d) return nullptr;
  return {{"time", jsonText(d->time)},
          {"point", jsonText(d->point)},
          {"quantity", jsonText(d->quantity)},
          {"expected", jsonNumber(d->expected)},
          {"actual", jsonNumber(d->actual)},
          {"difference", jsonNumber(d->difference)},
          {"tolerance", jsonNumber(d->tolerance)}};
}

OrderedJson jsonRun(const RunFacts& run) {
  return {{"manifest", jsonText(run.manifest)},
          {"program", jsonText(run.program)},
          {"gl", jsonText(run.gl)},
          {"lp_num_threads", jsonText(run.lpNumThreads)},
          {"overrides", jsonText(run.overrides)},
          {"shard", jsonText(run.shard)},
          {"seconds", jsonNumber(run.seconds)}};
}

OrderedJson jsonFrame(const FrameResult& f) {
  return {{"name", jsonText(f.name)},           {"scenario", jsonText(f.scenario)},
          {"time", jsonText(f.time)},           {"expect_differ", f.expectDiffer},
          {"outcome", outcomeName(f.outcome)},  {"message", jsonText(f.message)},
          {"numbers", jsonNumbers(f.numbers)},  {"files", jsonFiles(f.files)},
          {"reference", jsonText(f.reference)}, {"reproduce", jsonTexts(f.reproduce)},
          {"seconds", jsonNumber(f.seconds)}};
}

OrderedJson jsonState(const StateResult& s) {
  return {{"name", jsonText(s.name)},
          {"scenario", jsonText(s.scenario)},
          {"times", jsonTexts(s.times)},
          {"outcome", outcomeName(s.outcome)},
          {"message", jsonText(s.message)},
          {"first_beyond", jsonDeviation(s.firstBeyond)},
          {"largest", jsonDeviation(s.largest)},
          {"values", s.values},
          {"files", jsonFiles(s.files)},
          {"reference", jsonText(s.reference)},
          {"reproduce", jsonTexts(s.reproduce)},
          {"seconds", jsonNumber(s.seconds)}};
}

OrderedJson jsonCounts(const GoldenResults::Counts& c) {
  return {{"passed", c.passed}, {"failed", c.failed}, {"missing", c.missing}, {"error", c.error}};
}

// ---- reading ----------------------------------------------------------------------------------

std::vector<std::string> readTexts(const JsonAt& at) {
  std::vector<std::string> texts;
  for (std::size_t i = 0, n = at.arraySize(); i < n; ++i) texts.push_back(at.element(i).text());
  return texts;
}

Outcome readOutcome(const JsonAt& at) {
  const std::string name = at.text();
  const std::optional<Outcome> outcome = outcomeFromName(name);
  if (!outcome)
    at.fail(fmt::format("unknown outcome {} (passed, failed, missing or error)", report::quotedExcerpt(name)));
  return *outcome;
}

// A kept file's path: relative to the report folder and inside it, in the form the writer gives
// (components separated by '/', none empty, "." or ".."). That it leads through no symbolic link
// out of the folder is readResults' check (leavesFolder), made where there is a folder.
std::string readKeptPath(const JsonAt& at) {
  const std::string path = at.text();
  if (path.empty()) return path;  // not kept
  if (path.find('\0') != std::string::npos) at.fail("holds a NUL byte");
  if (path.find('\\') != std::string::npos) at.fail("holds a backslash: kept files are named with '/'");
  if (path.front() == '/') at.fail("is an absolute path: kept files are relative to the report folder");
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    const std::string_view component = std::string_view(path).substr(start, end - start);
    if (component == "..") at.fail("leaves the report folder (a \"..\" component)");
    if (component.empty() || component == ".") at.fail("is not a plain relative path (an empty or \".\" component)");
    start = end + 1;
  }
  return path;
}

KeptFiles readFiles(const JsonAt& at) {
  at.requireObject({"actual", "expected", "diff"});
  return {readKeptPath(at.member("actual")), readKeptPath(at.member("expected")), readKeptPath(at.member("diff"))};
}

// Whether the kept file `path` (which readKeptPath accepted) resolves, through symbolic links in
// the folder, to somewhere outside it.
bool leavesFolder(const std::filesystem::path& folder, const std::string& path) {
  std::error_code error;
  const std::filesystem::path inside = std::filesystem::weakly_canonical(folder / path, error);
  const std::filesystem::path base = std::filesystem::weakly_canonical(folder, error);
  if (error) return false;
  const std::filesystem::path relative = inside.lexically_relative(base);
  return relative.empty() || *relative.begin() == "..";
}

// Refuses results whose kept files lead out of `folder` through a symbolic link, naming the field
// as the reader names it ("frames[1].files.actual").
void checkKeptInside(const GoldenResults& results, const std::filesystem::path& folder, const std::string& file) {
  auto check = [&](const KeptFiles& files, std::string_view list, std::size_t i) {
    for (const auto& [name, path] :
         {std::pair{"actual", &files.actual}, std::pair{"expected", &files.expected}, std::pair{"diff", &files.diff}}) {
      if (!path->empty() && leavesFolder(folder, *path)) {
        throw std::invalid_argument(fmt::format(
            "{}: {}[{}].files.{}: leaves the report folder (through a symbolic link)", file, list, i, name));
      }
    }
  };
  for (std::size_t i = 0; i < results.frames.size(); ++i) check(results.frames[i].files, "frames", i);
  for (std::size_t i = 0; i < results.states.size(); ++i) check(results.states[i].files, "states", i);
}

std::optional<FrameNumbers> readNumbers(const JsonAt& at) {
  if (at.value.is_null()) return std::nullopt;
  at.requireObject({"threshold", "max_share", "differing", "pixels", "share", "largest", "box", "width", "height"});
  FrameNumbers n;
  n.threshold = int(at.member("threshold").integer(0, 255));
  n.maxShare = at.member("max_share").number(0.0, 1.0);
  n.width = int(at.member("width").integer(0, std::numeric_limits<int>::max()));
  n.height = int(at.member("height").integer(0, std::numeric_limits<int>::max()));
  n.pixels = at.member("pixels").integer();
  n.differing = at.member("differing").integer(0, n.pixels);
  n.share = at.member("share").number(0.0, 1.0);
  n.largest = int(at.member("largest").integer(0, 255));
  const JsonAt box = at.member("box");
  if (!box.value.is_null()) {
    if (box.arraySize() != 4) box.fail("is not null nor 4 integers x0, y0, x1, y1");
    std::array<int, 4> corners{};
    for (std::size_t i = 0; i < 4; ++i) {
      corners[i] = int(box.element(i).integer(0, (i % 2 == 0 ? n.width : n.height) - 1));
    }
    if (corners[0] > corners[2] || corners[1] > corners[3]) box.fail("has x0 > x1 or y0 > y1");
    n.box = corners;
  }
  return n;
}

std::optional<StateDeviation> readDeviation(const JsonAt& at) {
  if (at.value.is_null()) return std::nullopt;
  at.requireObject({"time", "point", "quantity", "expected", "actual", "difference", "tolerance"});
  return StateDeviation{at.member("time").text(),       at.member("point").text(),    at.member("quantity").text(),
                        at.member("expected").number(), at.member("actual").number(), at.member("difference").number(),
                        at.member("tolerance").number()};
}

RunFacts readRun(const JsonAt& at) {
  at.requireObject({"manifest", "program", "gl", "lp_num_threads", "overrides", "shard", "seconds"});
  return {at.member("manifest").text(),       at.member("program").text(),   at.member("gl").text(),
          at.member("lp_num_threads").text(), at.member("overrides").text(), at.member("shard").text(),
          at.member("seconds").number()};
}

FrameResult readFrame(const JsonAt& at) {
  at.requireObject({"name", "scenario", "time", "expect_differ", "outcome", "message", "numbers", "files", "reference",
                    "reproduce", "seconds"});
  FrameResult f;
  f.name = at.member("name").text();
  f.scenario = at.member("scenario").text();
  f.time = at.member("time").text();
  f.expectDiffer = at.member("expect_differ").boolean();
  f.outcome = readOutcome(at.member("outcome"));
  f.message = at.member("message").text();
  f.numbers = readNumbers(at.member("numbers"));
  f.files = readFiles(at.member("files"));
  f.reference = at.member("reference").text();
  f.reproduce = readTexts(at.member("reproduce"));
  f.seconds = at.member("seconds").number();
  return f;
}

StateResult readState(const JsonAt& at) {
  at.requireObject({"name", "scenario", "times", "outcome", "message", "first_beyond", "largest", "values", "files",
                    "reference", "reproduce", "seconds"});
  StateResult s;
  s.name = at.member("name").text();
  s.scenario = at.member("scenario").text();
  s.times = readTexts(at.member("times"));
  s.outcome = readOutcome(at.member("outcome"));
  s.message = at.member("message").text();
  s.firstBeyond = readDeviation(at.member("first_beyond"));
  s.largest = readDeviation(at.member("largest"));
  s.values = at.member("values").integer();
  s.files = readFiles(at.member("files"));
  s.reference = at.member("reference").text();
  s.reproduce = readTexts(at.member("reproduce"));
  s.seconds = at.member("seconds").number();
  return s;
}

}  // namespace

std::string report::resultsJson(const GoldenResults& results) {
  OrderedJson runs = OrderedJson::array(), frames = OrderedJson::array(), states = OrderedJson::array();
  for (const RunFacts& run : results.runs) runs.push_back(jsonRun(run));
  for (const FrameResult& frame : results.frames) frames.push_back(jsonFrame(frame));
  for (const StateResult& state : results.states) states.push_back(jsonState(state));
  const OrderedJson json = {
      {"format", kResultsFormat}, {"version", kResultsVersion},  {"counts", jsonCounts(results.counts())},
      {"runs", std::move(runs)},  {"frames", std::move(frames)}, {"states", std::move(states)}};
  return json.dump(2) + "\n";
}

GoldenResults parseResultsJson(std::string_view text, const std::string& file) {
  const nlohmann::json json = parseJsonText(text, file, report::kMaxResultsDepth);
  const JsonAt top{json, "", file};
  top.requireObject({"format", "version", "counts", "runs", "frames", "states"});
  if (top.member("format").text() != report::kResultsFormat) {
    top.member("format").fail(fmt::format("is not \"{}\": not a golden results file", report::kResultsFormat));
  }
  const JsonAt version = top.member("version");
  if (!version.value.is_number_integer() || version.value.get<std::int64_t>() != report::kResultsVersion) {
    version.fail(
        fmt::format("is {}, and this particles reads version {}", valueText(version.value), report::kResultsVersion));
  }
  GoldenResults results;
  const JsonAt runs = top.member("runs"), frames = top.member("frames"), states = top.member("states");
  for (std::size_t i = 0, n = runs.arraySize(); i < n; ++i) results.runs.push_back(readRun(runs.element(i)));
  for (std::size_t i = 0, n = frames.arraySize(); i < n; ++i) results.frames.push_back(readFrame(frames.element(i)));
  for (std::size_t i = 0, n = states.arraySize(); i < n; ++i) results.states.push_back(readState(states.element(i)));

  const JsonAt counts = top.member("counts");
  counts.requireObject({"passed", "failed", "missing", "error"});
  const GoldenResults::Counts c = results.counts();
  if (counts.member("passed").integer() != c.passed || counts.member("failed").integer() != c.failed ||
      counts.member("missing").integer() != c.missing || counts.member("error").integer() != c.error) {
    counts.fail(fmt::format("do not match the results ({} passed, {} failed, {} missing, {} error)", c.passed, c.failed,
                            c.missing, c.error));
  }
  return results;
}

GoldenResults readResults(const std::filesystem::path& folder, std::uintmax_t maxInputMiB) {
  const std::filesystem::path path = folder / kResultsJson;
  const std::string file = path.string();
  std::string text;
  try {
    // Written by `golden check`: a FIFO or device in its place is refused, never waited on.
    text = input::readTextFile(path, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    throw std::invalid_argument(fmt::format("{}: {}", file, e.what()));
  }
  GoldenResults results = parseResultsJson(text, file);
  checkKeptInside(results, folder, file);
  return results;
}

std::string summaryLine(const GoldenResults& results, const std::filesystem::path& folder) {
  const GoldenResults::Counts c = results.counts();
  std::string outcomes = fmt::format("{} passed", c.passed);
  if (c.failed > 0) outcomes += fmt::format(", {} failed", c.failed);
  if (c.missing > 0) outcomes += fmt::format(", {} missing", c.missing);
  if (c.error > 0) outcomes += ", " + report::countText(c.error, "error", "errors");
  return fmt::format(
      "golden: {}, {}: {} (report: {})", report::countText(long(results.frames.size()), "frame", "frames"),
      report::countText(long(results.states.size()), "state", "states"), outcomes, (folder / kReportHtml).string());
}

}  // namespace particles::golden
