// The golden report folder (src/golden/results.hpp): report.html, junit.xml and results.json
// written from results, results.json read back field for field, hostile strings escaped in all
// three, readResults refusing what is not a results file, and the sample report that
// tests/golden/browser_test.py opens in Chromium (CTest's golden-report:* tests).
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

#include "cli_support.hpp"
#include "golden/check.hpp"
#include "golden/report_text.hpp"
#include "golden/results.hpp"
#include "golden/results_json.hpp"
#include "output/output_error.hpp"
#include "render/image.hpp"
#include "render/image_compare.hpp"
#include "render/png_io.hpp"

namespace fs = std::filesystem;
using namespace particles::golden;
using particles::render::Image;

namespace {

struct TempDir {
  fs::path dir;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "particles_golden_report_XXXXXX").string();
    REQUIRE(::mkdtemp(pattern.data()) != nullptr);
    dir = pattern;
  }
  ~TempDir() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

std::string readAll(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

void writeAll(const fs::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
}

std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + what.size())) ++n;
  return n;
}

// An independent check of UTF-8 (RFC 3629): no overlong forms, surrogates or code points past U+10FFFF.
bool isValidUtf8(const std::string& text) {
  for (std::size_t i = 0; i < text.size();) {
    const auto b = [&](std::size_t k) { return k < text.size() ? unsigned(std::uint8_t(text[k])) : 0u; };
    const unsigned c = b(i);
    int n = 0;
    unsigned code = 0, minimum = 0;
    if (c < 0x80) {
      ++i;
      continue;
    } else if ((c & 0xE0) == 0xC0) {
      n = 1, code = c & 0x1F, minimum = 0x80;
    } else if ((c & 0xF0) == 0xE0) {
      n = 2, code = c & 0x0F, minimum = 0x800;
    } else if ((c & 0xF8) == 0xF0) {
      n = 3, code = c & 0x07, minimum = 0x10000;
    } else {
      return false;
    }
    for (int k = 1; k <= n; ++k) {
      if ((b(i + k) & 0xC0) != 0x80) return false;
      code = (code << 6) | (b(i + k) & 0x3F);
    }
    if (code < minimum || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += n + 1;
  }
  return true;
}

// ---- results to write --------------------------------------------------------------------------

RunFacts sampleRun() {
  return {"golden/manifest.yaml", "particles 0.1.0", "egl: llvmpipe (LLVM 15.0.6, 256 bits)", "", "", "", 12.5};
}

FrameNumbers numbersOf(const particles::render::ImageComparison& c, int threshold, double maxShare) {
  return particles::golden::frameNumbersOf(c, {threshold, maxShare});
}

// Every field set, optionals both present and absent, numbers that need all their digits.
GoldenResults everyField() {
  GoldenResults r;
  r.runs = {sampleRun(), {"golden/manifest.yaml", "particles 0.1.0", "osmesa", "1", "--raster tiles", "2/3", 0.1}};
  FrameResult failed;
  failed.name = "cloth_t2.5";
  failed.scenario = "scenarios/cloth.yaml";
  failed.time = "2.5";
  failed.outcome = Outcome::failed;
  failed.message = "0.1235 % of the pixels differ by more than 16 (bound 0.02 %)";
  failed.numbers = FrameNumbers{16, 0.0002, 95, 76800, 95.0 / 76800.0, 54, std::array<int, 4>{3, 4, 40, 50}, 320, 240};
  failed.files = {"frames/cloth_t2.5.actual.png", "frames/cloth_t2.5.expected.png", "frames/cloth_t2.5.diff.png"};
  failed.reference = "golden/cloth_t2.5.png";
  failed.reproduce = {"particles render scenarios/cloth.yaml --at 2.5 -o cloth.png",
                      "particles compare golden/cloth_t2.5.png cloth.png"};
  failed.seconds = 0.1 + 0.2;
  FrameResult control;
  control.name = "cloth_t2.5:next-step";
  control.expectDiffer = true;
  control.outcome = Outcome::passed;
  control.numbers = FrameNumbers{16, 0.0002, 0, 76800, 0.0, 0, std::nullopt, 320, 240};
  FrameResult error;
  error.name = "broken";
  error.outcome = Outcome::error;
  error.message = "scenarios/broken.yaml:3:7: unknown key";
  StateResult state;
  state.name = "pendulum";
  state.scenario = "scenarios/pendulum.yaml";
  state.times = {"0.5", "1", "1e-3"};
  state.outcome = Outcome::failed;
  state.message = "bob x at t 0.5 differs by 2e-6, tolerance 1e-6";
  state.firstBeyond = StateDeviation{"0.5", "bob", "x", 1.0 / 3.0, 1.0 / 3.0 + 2e-6, 2e-6, 1e-6};
  state.largest = StateDeviation{"1",
                                 "cloth[3][4]",
                                 "omega",
                                 std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::infinity(),
                                 -std::numeric_limits<double>::infinity(),
                                 1e-300};
  state.values = 123456789012L;
  state.files = {"states/pendulum.actual.csv", "states/pendulum.expected.csv", ""};
  state.reference = "golden/states/pendulum.csv";
  state.reproduce = {"particles run scenarios/pendulum.yaml --trace pendulum.csv"};
  state.seconds = 1e-9;
  StateResult missing;
  missing.name = "new_state";
  missing.outcome = Outcome::missing;
  r.frames = {failed, control, error};
  r.states = {state, missing};
  return r;
}

void checkSameNumber(double a, double b) {
  if (std::isnan(a)) {
    CHECK(std::isnan(b));
  } else {
    CHECK(a == b);  // exactly: results.json keeps every digit
  }
}

void checkSameFiles(const KeptFiles& a, const KeptFiles& b) {
  CHECK(a.actual == b.actual);
  CHECK(a.expected == b.expected);
  CHECK(a.diff == b.diff);
}

void checkSameDeviation(const std::optional<StateDeviation>& a, const std::optional<StateDeviation>& b) {
  REQUIRE(a.has_value() == b.has_value());
  if (!a) return;
  CHECK(a->time == b->time);
  CHECK(a->point == b->point);
  CHECK(a->quantity == b->quantity);
  checkSameNumber(a->expected, b->expected);
  checkSameNumber(a->actual, b->actual);
  checkSameNumber(a->difference, b->difference);
  checkSameNumber(a->tolerance, b->tolerance);
}

// The fields frames and states share.
template <typename Result>
void checkSameCommonFields(const Result& x, const Result& y) {
  CHECK(x.name == y.name);
  CHECK(x.scenario == y.scenario);
  CHECK(x.outcome == y.outcome);
  CHECK(x.message == y.message);
  checkSameFiles(x.files, y.files);
  CHECK(x.reference == y.reference);
  CHECK(x.reproduce == y.reproduce);
  checkSameNumber(x.seconds, y.seconds);
}

void checkSameResults(const GoldenResults& a, const GoldenResults& b) {
  REQUIRE(a.runs.size() == b.runs.size());
  for (std::size_t i = 0; i < a.runs.size(); ++i) {
    CAPTURE(i);
    CHECK(a.runs[i].manifest == b.runs[i].manifest);
    CHECK(a.runs[i].program == b.runs[i].program);
    CHECK(a.runs[i].gl == b.runs[i].gl);
    CHECK(a.runs[i].lpNumThreads == b.runs[i].lpNumThreads);
    CHECK(a.runs[i].overrides == b.runs[i].overrides);
    CHECK(a.runs[i].shard == b.runs[i].shard);
    checkSameNumber(a.runs[i].seconds, b.runs[i].seconds);
  }
  REQUIRE(a.frames.size() == b.frames.size());
  for (std::size_t i = 0; i < a.frames.size(); ++i) {
    CAPTURE(i);
    const FrameResult &x = a.frames[i], &y = b.frames[i];
    checkSameCommonFields(x, y);
    CHECK(x.time == y.time);
    CHECK(x.expectDiffer == y.expectDiffer);
    REQUIRE(x.numbers.has_value() == y.numbers.has_value());
    if (x.numbers) {
      CHECK(x.numbers->threshold == y.numbers->threshold);
      checkSameNumber(x.numbers->maxShare, y.numbers->maxShare);
      CHECK(x.numbers->differing == y.numbers->differing);
      CHECK(x.numbers->pixels == y.numbers->pixels);
      checkSameNumber(x.numbers->share, y.numbers->share);
      CHECK(x.numbers->largest == y.numbers->largest);
      CHECK(x.numbers->box == y.numbers->box);
      CHECK(x.numbers->width == y.numbers->width);
      CHECK(x.numbers->height == y.numbers->height);
    }
  }
  REQUIRE(a.states.size() == b.states.size());
  for (std::size_t i = 0; i < a.states.size(); ++i) {
    CAPTURE(i);
    const StateResult &x = a.states[i], &y = b.states[i];
    checkSameCommonFields(x, y);
    CHECK(x.times == y.times);
    checkSameDeviation(x.firstBeyond, y.firstBeyond);
    checkSameDeviation(x.largest, y.largest);
    CHECK(x.values == y.values);
  }
}

// ---- the sample report -------------------------------------------------------------------------

// A 64×48 frame: a dark background and a disc of radius 8 centred at (cx, cy).
Image discFrame(int cx, int cy) {
  Image image(64, 48);
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      std::uint8_t* p = image.pixel(x, y);
      const bool inside = (x - cx) * (x - cx) + (y - cy) * (y - cy) <= 64;
      p[0] = inside ? 230 : 20, p[1] = inside ? 180 : 22, p[2] = inside ? 60 : 34, p[3] = 255;
    }
  }
  return image;
}

// writeSampleFolder's states: one failed, one passed.
std::vector<StateResult> sampleStates() {
  StateResult stateFailed;
  stateFailed.name = "pendulum_state";
  stateFailed.scenario = "scenarios/pendulum.yaml";
  stateFailed.times = {"0.5", "1"};
  stateFailed.outcome = Outcome::failed;
  stateFailed.message = "bob x at t 0.5: difference 2e-06 beyond tolerance 1e-06";
  stateFailed.firstBeyond = StateDeviation{"0.5", "bob", "x", 0.3333333333, 0.3333353333, 2e-6, 1e-6};
  stateFailed.largest = stateFailed.firstBeyond;
  stateFailed.values = 12;
  stateFailed.files = {"states/pendulum.actual.csv", "states/pendulum.expected.csv", ""};
  stateFailed.reference = "golden/states/pendulum.csv";
  stateFailed.reproduce = {"particles run scenarios/pendulum.yaml --trace pendulum.csv"};
  stateFailed.seconds = 0.05;
  StateResult statePassed;
  statePassed.name = "cloth_state";
  statePassed.scenario = "scenarios/cloth.yaml";
  statePassed.times = {"1", "2.5"};
  statePassed.outcome = Outcome::passed;
  statePassed.largest = StateDeviation{"2.5", "cloth[3][4]", "vy", -0.25, -0.2500000001, -1e-10, 1e-6};
  statePassed.values = 2400;
  statePassed.reference = "golden/states/cloth.csv";
  statePassed.seconds = 0.2;
  return {stateFailed, statePassed};
}

// What tests/golden/browser_test.py and junit_test.py check (golden/CMakeLists.txt gives the counts
// of its junit.xml): frames failed, missing (with only its actual frame, in a file whose name needs
// escaping in a URL), passed, a control that passed and an error; states failed and passed.
GoldenResults writeSampleFolder(const fs::path& folder) {
  fs::create_directories(folder / "frames");
  fs::create_directories(folder / "states");
  const Image expected = discFrame(24, 24), actual = discFrame(30, 22);
  const particles::render::ImageComparison c = particles::render::compareImages(expected, actual);
  particles::render::writePng(folder / "frames/cloth_t2.5.expected.png", expected);
  particles::render::writePng(folder / "frames/cloth_t2.5.actual.png", actual);
  particles::render::writePng(folder / "frames/cloth_t2.5.diff.png", particles::render::diffImage(expected, actual));
  particles::render::writePng(folder / "frames/soft body #9 & 100%.actual.png", discFrame(40, 30));
  const Image perturbed = discFrame(25, 24);
  const particles::render::ImageComparison cc = particles::render::compareImages(expected, perturbed);
  particles::render::writePng(folder / "frames/cloth_t2.5.next-step.actual.png", perturbed);
  particles::render::writePng(folder / "frames/cloth_t2.5.next-step.diff.png",
                              particles::render::diffImage(expected, perturbed));
  writeAll(folder / "states/pendulum.actual.csv", "t,point,x,y,vx,vy\n0.5,bob,0.3333353333,-0.94,0.1,0.2\n");
  writeAll(folder / "states/pendulum.expected.csv", "t,point,x,y,vx,vy\n0.5,bob,0.3333333333,-0.94,0.1,0.2\n");

  GoldenResults r;
  r.runs = {sampleRun()};
  const double maxShare = particles::render::kDefaultMaxShare;
  const int threshold = particles::render::kDefaultThreshold;
  FrameResult failed;
  failed.name = "cloth_t2.5";
  failed.scenario = "scenarios/cloth.yaml";
  failed.time = "2.5";
  failed.outcome = Outcome::failed;
  failed.numbers = numbersOf(c, threshold, maxShare);
  failed.message = "differs from its reference: more than 0.02 % of the pixels differ";
  failed.files = {"frames/cloth_t2.5.actual.png", "frames/cloth_t2.5.expected.png", "frames/cloth_t2.5.diff.png"};
  failed.reference = "golden/cloth_t2.5.png";
  failed.reproduce = {"particles render scenarios/cloth.yaml --at 2.5 -o cloth_t2.5.png",
                      "particles compare golden/cloth_t2.5.png cloth_t2.5.png --diff cloth_t2.5.diff.png"};
  failed.seconds = 0.82;
  FrameResult missing;
  missing.name = "soft body #9 & 100% <new>";
  missing.scenario = "scenarios/soft_body.yaml";
  missing.time = "9";
  missing.outcome = Outcome::missing;
  missing.message =
      "no reference golden/soft_body_t9.png: create it with `particles golden update --missing "
      "golden/manifest.yaml` and review it";
  missing.files.actual = "frames/soft body #9 & 100%.actual.png";
  missing.reference = "golden/soft_body_t9.png";
  missing.reproduce = {"particles render scenarios/soft_body.yaml --at 9 -o 'soft body.png'"};
  missing.seconds = 0.41;
  FrameResult passed;
  passed.name = "rigid_chain_t0.65";
  passed.scenario = "scenarios/rigid_chain.yaml";
  passed.time = "0.65";
  passed.outcome = Outcome::passed;
  passed.numbers = numbersOf(particles::render::compareImages(expected, expected), threshold, maxShare);
  passed.reference = "golden/rigid_chain_t0.65.png";
  passed.seconds = 0.37;
  FrameResult control;
  control.name = "cloth_t2.5:next-step";
  control.scenario = "scenarios/cloth.yaml";
  control.time = "2.51";
  control.expectDiffer = true;
  control.outcome = Outcome::passed;
  control.numbers = numbersOf(cc, threshold, maxShare);
  control.files = {"frames/cloth_t2.5.next-step.actual.png", "", "frames/cloth_t2.5.next-step.diff.png"};
  control.reference = "golden/cloth_t2.5.png";
  control.seconds = 0.79;
  FrameResult error;
  error.name = "broken_t1";
  error.scenario = "scenarios/broken.yaml";
  error.time = "1";
  error.outcome = Outcome::error;
  // As a scenario with stray bytes would put it: invalid UTF-8 and a control character, which every
  // file must replace (and xmllint, junitparser and Chromium then read).
  error.message = "scenarios/broken.yaml:3:7: forces[0]: unknown key 'gravty\xff\x01' (did you mean 'gravity'?)";
  error.reference = "golden/broken_t1.png";
  error.reproduce = {"particles check scenarios/broken.yaml"};
  error.seconds = 0.01;
  r.frames = {failed, missing, passed, control, error};

  r.states = sampleStates();
  writeReport(folder, r);
  return r;
}

// results.json of a folder holding one frame result, its text for a test to spoil.
std::string oneFrameJson(const fs::path& folder) {
  GoldenResults r;
  r.runs = {sampleRun()};
  FrameResult f;
  f.name = "a";
  f.outcome = Outcome::failed;
  f.numbers = FrameNumbers{16, 0.0002, 1, 4, 0.25, 54, std::array<int, 4>{0, 0, 1, 1}, 2, 2};
  f.files = {"frames/a.png", "", ""};
  r.frames = {f};
  writeReport(folder, r);
  return readAll(folder / "results.json");
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  REQUIRE_MESSAGE(at != std::string::npos, "no " << from << " in " << text);
  return text.replace(at, from.size(), to);
}

// readResults' message for a folder whose results.json is `text`.
std::string refusal(const fs::path& folder, const std::string& text) {
  writeAll(folder / "results.json", text);
  try {
    readResults(folder, 64);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  FAIL("read without an error: " << text.substr(0, 200));
  return "";
}

// `depth` arrays, each the only value of the one around it.
std::string nested(std::size_t depth) {
  return std::string(depth, '[') + std::string(depth, ']');
}

// Every path under `dir`, relative to it, sorted, one a line: what a refused command must leave
// as it was.
std::string listing(const fs::path& dir) {
  std::vector<std::string> paths;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    paths.push_back(e.path().lexically_relative(dir).string());
  std::sort(paths.begin(), paths.end());
  std::string text;
  for (const std::string& path : paths) text += path + "\n";
  return text;
}

}  // namespace

TEST_CASE("golden report: results.json reads back as it was written, field for field") {
  TempDir t;
  const GoldenResults written = everyField();
  writeReport(t.dir, written);
  const GoldenResults read = readResults(t.dir, 64);
  checkSameResults(written, read);
  // The same results give the same bytes, in every file.
  const std::string html = readAll(t.dir / "report.html"), junit = readAll(t.dir / "junit.xml"),
                    json = readAll(t.dir / "results.json");
  writeReport(t.dir, read);
  CHECK(readAll(t.dir / "report.html") == html);
  CHECK(readAll(t.dir / "junit.xml") == junit);
  CHECK(readAll(t.dir / "results.json") == json);
  CHECK(json.starts_with("{\n  \"format\": \"particles-golden-results\",\n  \"version\": 1,\n"));
  CHECK(json.find("\"expected\": \"nan\"") != std::string::npos);
  // No temporary left beside them.
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(t.dir)) ++entries;
  CHECK(entries == 3);
}

TEST_CASE("golden report: names, messages and commands with any bytes are escaped in all three files") {
  TempDir t;
  GoldenResults r = everyField();
  const std::string hostile = "<script>alert(\"x&y\")</script> 'q' \xff\xfe\x01 \xe2\x82 end";
  r.frames[0].name = hostile;
  r.frames[0].message = "bad \x1b[31m red\r\n<b>";
  r.frames[0].reproduce = {"particles render 'a b' && echo \"<x>\" > /dev/null"};
  r.frames[0].files.actual = "frames/a b&c%<d>#e.png";
  r.states[0].name = hostile;
  r.runs[0].overrides = "--set \"name=<x>\"";
  writeReport(t.dir, r);
  const std::string html = readAll(t.dir / "report.html"), junit = readAll(t.dir / "junit.xml"),
                    json = readAll(t.dir / "results.json");
  for (const auto& [file, text] :
       {std::pair{std::string("report.html"), &html}, std::pair{std::string("junit.xml"), &junit},
        std::pair{std::string("results.json"), &json}}) {
    CAPTURE(file);
    CHECK(isValidUtf8(*text));
    CHECK(text->find("\x01") == std::string::npos);  // JSON as \u0001, markup as U+FFFD
    CHECK(text->find("\x1b") == std::string::npos);
    if (file != "results.json") CHECK(text->find("<script>alert") == std::string::npos);
  }
  // The page's only script is its own.
  CHECK(countOf(html, "<script>") == 1);
  CHECK(html.find("&lt;script&gt;alert(&quot;x&amp;y&quot;)&lt;/script&gt; &#39;q&#39; \xef\xbf\xbd\xef\xbf\xbd"
                  "\xef\xbf\xbd \xef\xbf\xbd end") != std::string::npos);
  CHECK(html.find("echo &quot;&lt;x&gt;&quot; &gt; /dev/null") != std::string::npos);
  CHECK(html.find("src=\"frames/a%20b%26c%25%3Cd%3E%23e.png\"") != std::string::npos);
  CHECK(html.find("--set &quot;name=&lt;x&gt;&quot;") != std::string::npos);
  // XML: in attributes line breaks are references, in text they stay.
  CHECK(junit.find("name=\"&lt;script&gt;alert(&quot;x&amp;y&quot;)&lt;/script&gt;") != std::string::npos);
  CHECK(junit.find("message=\"bad \xef\xbf\xbd[31m red&#13;&#10;&lt;b&gt;\"") != std::string::npos);
  const auto control = std::find_if(
      junit.begin(), junit.end(), [](char c) { return std::uint8_t(c) < 0x20 && c != '\n' && c != '\t' && c != '\r'; });
  CHECK_MESSAGE(control == junit.end(), "a control byte at " << (control - junit.begin()));
  // JSON keeps control characters (escaped) and replaces invalid UTF-8.
  const GoldenResults read = readResults(t.dir, 64);
  CHECK(read.frames[0].name == "<script>alert(\"x&y\")</script> 'q' \xef\xbf\xbd\xef\xbf\xbd\x01 \xef\xbf\xbd end");
  CHECK(read.frames[0].message == "bad \x1b[31m red\r\n<b>");
  CHECK(read.frames[0].files.actual == "frames/a b&c%<d>#e.png");
}

TEST_CASE("golden report: readResults refuses what is not a results file, naming it and the place") {
  TempDir t;
  const std::string valid = oneFrameJson(t.dir);
  const std::string file = (t.dir / "results.json").string();
  CHECK(readResults(t.dir, 64).frames.size() == 1);

  CHECK(refusal(t.dir, "{ \"format\": ").starts_with(file + ": not JSON: parse error at line 1, column 13"));
  CHECK(refusal(t.dir, "[1, 2]") == file + ": is not an object");
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": 2")) ==
        file + ": version: is 2, and this particles reads version 1");
  CHECK(refusal(t.dir, replaced(valid, "particles-golden-results", "sweep")) ==
        file + ": format: is not \"particles-golden-results\": not a golden results file");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", "\"../x.png\"")) ==
        file + ": frames[0].files.actual: leaves the report folder (a \"..\" component)");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", "\"frames/../../x.png\"")) ==
        file + ": frames[0].files.actual: leaves the report folder (a \"..\" component)");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", "\"/etc/passwd\"")) ==
        file + ": frames[0].files.actual: is an absolute path: kept files are relative to the report folder");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", R"("frames\\a.png")")) ==
        file + ": frames[0].files.actual: holds a backslash: kept files are named with '/'");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", R"("a\u0000.png")")) ==
        file + ": frames[0].files.actual: holds a NUL byte");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", "\"./a.png\""))
            .find("frames[0].files.actual: is not a "
                  "plain relative path") != std::string::npos);
  CHECK(refusal(t.dir, replaced(valid, "\"outcome\": \"failed\"", "\"outcome\": \"flaky\"")) ==
        file + ": frames[0].outcome: unknown outcome \"flaky\" (passed, failed, missing or error)");
  CHECK(refusal(t.dir, replaced(valid, "\"threshold\": 16", "\"threshold\": \"16\"")) ==
        file + ": frames[0].numbers.threshold: is not an integer");
  CHECK(refusal(t.dir, replaced(valid, "\"threshold\": 16", "\"threshold\": 300")) ==
        file + ": frames[0].numbers.threshold: is not an integer from 0 to 255");
  CHECK(refusal(t.dir, replaced(valid, "\"name\": \"a\"", "\"nmae\": \"a\"")) ==
        file + ": frames[0]: has an unknown key \"nmae\"");
  CHECK(refusal(t.dir, replaced(valid, "\"expect_differ\": false", "\"expect_differ\": 0")) ==
        file + ": frames[0].expect_differ: is not true or false");
  CHECK(refusal(t.dir, replaced(valid, "\"failed\": 1", "\"failed\": 2")).starts_with(file + ": counts: do not match"));
  CHECK(refusal(t.dir, replaced(valid, "\"runs\": [", "\"runs\": 3, \"x\": [")) == file + ": has an unknown key \"x\"");

  // A link inside the folder to outside it.
  TempDir outside;
  fs::create_directory_symlink(outside.dir, t.dir / "out");
  CHECK(refusal(t.dir, replaced(valid, "\"frames/a.png\"", "\"out/a.png\"")) ==
        file + ": frames[0].files.actual: leaves the report folder (through a symbolic link)");

  // 100 MiB (a sparse file) over a 64 MiB limit: refused from its size, nothing read.
  writeAll(t.dir / "results.json", "");
  fs::resize_file(t.dir / "results.json", 100u << 20);
  try {
    readResults(t.dir, 64);
    FAIL("a 100 MiB results.json was read");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()) == file +
                                       ": the file is larger than the input limit of 64 MiB; if it is meant to be, "
                                       "raise the limit with --max-input MIB");
  }
  // A FIFO with nobody writing is refused at once, not waited on.
  fs::remove(t.dir / "results.json");
  REQUIRE(::mkfifo((t.dir / "results.json").c_str(), 0600) == 0);
  CHECK_THROWS_WITH_AS(readResults(t.dir, 64),
                       (file + ": cannot read: it is a FIFO, where a regular file was expected").c_str(),
                       std::invalid_argument);
  fs::remove(t.dir / "results.json");
  CHECK_THROWS_WITH_AS(readResults(t.dir, 64), (file + ": cannot open: No such file or directory").c_str(),
                       std::invalid_argument);
}

TEST_CASE("golden report: junit.xml counts a missing reference as a failure and an error as an error") {
  TempDir t;
  const GoldenResults r = writeSampleFolder(t.dir);
  const std::string junit = readAll(t.dir / "junit.xml");
  CHECK(
      junit.starts_with("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"particles golden\" tests=\"7\" "
                        "failures=\"3\" errors=\"1\" skipped=\"0\""));
  CHECK(junit.find("<testsuite name=\"golden frames\" tests=\"5\" failures=\"2\" errors=\"1\" skipped=\"0\" "
                   "time=\"2.400\">") != std::string::npos);
  CHECK(junit.find("<testsuite name=\"golden states\" tests=\"2\" failures=\"1\" errors=\"0\" skipped=\"0\" "
                   "time=\"0.250\">") != std::string::npos);
  CHECK(countOf(junit, "<testcase classname=\"golden.frames\"") == 5);
  CHECK(countOf(junit, "<testcase classname=\"golden.states\"") == 2);
  CHECK(countOf(junit, "type=\"missing-reference\"") == 1);
  CHECK(countOf(junit, "<error message=") == 1);
  CHECK(countOf(junit, "type=\"golden\"") == 2);
  CHECK(junit.find("<testcase classname=\"golden.frames\" name=\"rigid_chain_t0.65\" time=\"0.370\"/>") !=
        std::string::npos);
  CHECK(junit.find("reproduce:\n  particles render scenarios/cloth.yaml --at 2.5 -o cloth_t2.5.png\n") !=
        std::string::npos);
  CHECK(junit.find("<property name=\"manifest\" value=\"golden/manifest.yaml\"/>") != std::string::npos);
  CHECK(r.counts().total() == 7);
}

TEST_CASE("golden report: the summary line") {
  TempDir t;
  const GoldenResults r = writeSampleFolder(t.dir);
  CHECK(summaryLine(r, "out") ==
        "golden: 5 frames, 2 states: 3 passed, 2 failed, 1 missing, 1 error (report: "
        "out/report.html)");
  GoldenResults one;
  one.frames.resize(1);
  one.frames[0].outcome = Outcome::passed;
  CHECK(summaryLine(one, "build/golden") == "golden: 1 frame, 0 states: 1 passed (report: build/golden/report.html)");
  one.frames.resize(3);  // Outcome::error by default
  CHECK(summaryLine(one, "r") == "golden: 3 frames, 0 states: 1 passed, 2 errors (report: r/report.html)");
}

TEST_CASE("golden report: the page puts failures first, labels controls, hides its widgets until its script runs") {
  TempDir t;
  writeSampleFolder(t.dir);
  const std::string html = readAll(t.dir / "report.html");
  const std::size_t failures = html.find("<h2>Not passed</h2>"), passed = html.find("<h2>Passed frames</h2>");
  REQUIRE(failures != std::string::npos);
  REQUIRE(passed != std::string::npos);
  CHECK(failures < passed);
  CHECK(html.find("<section class=\"result failed\" id=\"frame-0\">") < passed);
  CHECK(html.find("<section class=\"result missing\" id=\"frame-1\">") < passed);
  CHECK(html.find("<section class=\"result error\" id=\"frame-4\">") < passed);
  CHECK(html.find("<section class=\"result failed\" id=\"state-0\">") < passed);
  CHECK(html.find("rigid_chain_t0.65") > passed);
  CHECK(html.find("control: must differ") != std::string::npos);
  CHECK(countOf(html, "<div class=\"compare\" hidden") == 1);  // the one failure with both frames
  CHECK(html.find("<link rel=\"icon\" href=\"data:,\">") != std::string::npos);
  CHECK(html.find("http") == std::string::npos);  // nothing fetched
  CHECK(html.find("src=\"frames/soft%20body%20%239%20%26%20100%25.actual.png\"") != std::string::npos);
  CHECK(html.find("<pre><code>particles render scenarios/cloth.yaml --at 2.5 -o cloth_t2.5.png\n") !=
        std::string::npos);
  CHECK(html.find("<td class=\"n\">0.3333353333</td>") != std::string::npos);
}

TEST_CASE("golden report: a sample report for the browser test") {
  // With PARTICLES_GOLDEN_SAMPLE_REPORT=FOLDER (CTest's golden-report:sample), the sample report
  // is written there for tests/golden/browser_test.py and junit_test.py; without it, into a
  // scratch folder and checked here.
  if (const char* folder = std::getenv("PARTICLES_GOLDEN_SAMPLE_REPORT"); folder != nullptr && *folder != '\0') {
    writeSampleFolder(folder);
    MESSAGE("sample report: " << (fs::path(folder) / "report.html").string());
    return;
  }
  TempDir t;
  GoldenResults written = writeSampleFolder(t.dir);
  for (const std::string_view name : {kReportHtml, kJunitXml, kResultsJson}) {
    CHECK(fs::is_regular_file(t.dir / name));
  }
  // The error's stray byte comes back as U+FFFD, its control character as it was.
  const std::size_t stray = written.frames[4].message.find('\xff');
  REQUIRE(stray != std::string::npos);
  written.frames[4].message.replace(stray, 1, "\xef\xbf\xbd");
  checkSameResults(written, readResults(t.dir, 64));
  // Every kept file the results name is in the folder.
  for (const FrameResult& f : written.frames) {
    for (const std::string& file : {f.files.actual, f.files.expected, f.files.diff}) {
      if (!file.empty()) CHECK_MESSAGE(fs::is_regular_file(t.dir / file), file);
    }
  }
}

TEST_CASE("golden report: writing into a folder that is not there fails as an output error") {
  TempDir t;
  CHECK_THROWS_AS(writeReport(t.dir / "missing", everyField()), particles::output::OutputError);
}

TEST_CASE("golden report: a value in a message is quoted by at most 80 bytes, whole characters, controls escaped") {
  using report::kMaxQuotedBytes;
  using report::quotedExcerpt;
  CHECK(quotedExcerpt("flaky") == "\"flaky\"");
  CHECK(quotedExcerpt("a\"b\\c\n\t\r\x1b[31m\x7f\xc2\x9b") == R"("a\"b\\c\n\t\r\u001b[31m\u007f\u009b")");
  CHECK(quotedExcerpt("it's \"x\"", '\'') == R"('it\'s "x"')");
  CHECK(quotedExcerpt("bad \xff byte") == "\"bad \xef\xbf\xbd byte\"");
  const std::string fits(kMaxQuotedBytes, 'x');
  CHECK(quotedExcerpt(fits) == "\"" + fits + "\"");
  // One byte more: cut to leave room for the 3 bytes of "…".
  CHECK(quotedExcerpt(fits + "y") == "\"" + std::string(kMaxQuotedBytes - 3, 'x') + "…\" (81 bytes)");
  // A 2-byte character is not cut in two: 38 of them (76 bytes) fit beside "…", 39 do not.
  std::string accents;
  for (int i = 0; i < 100; ++i) accents += "é";
  std::string kept;
  for (int i = 0; i < 38; ++i) kept += "é";
  CHECK(quotedExcerpt(accents) == "\"" + kept + "…\" (200 bytes)");
  // Escapes count as what they take: 12 "\u0001" (72 bytes) fit, a 13th does not.
  std::string escapes;
  for (int i = 0; i < 12; ++i) escapes += "\\u0001";
  CHECK(quotedExcerpt(std::string(1'000'000, '\x01')) == "\"" + escapes + "…\" (1000000 bytes)");
  CHECK(isValidUtf8(quotedExcerpt(std::string(100, '\xe2'))));
}

TEST_CASE("golden report: results.json nested more than 64 deep is refused where it passes the limit") {
  TempDir t;
  const std::string valid = oneFrameJson(t.dir);
  const std::string file = (t.dir / "results.json").string();
  const std::size_t limit = report::kMaxResultsDepth;
  REQUIRE(limit == 64);  // the messages below say so
  // At the limit (the file's object is the first level): read, and refused for what "version" is.
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": " + nested(limit - 1))) ==
        file + ": version: is an array of 1 value, and this particles reads version 1");
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": {\"a\": []}")) ==
        file + ": version: is an object of 1 key, and this particles reads version 1");
  // One level more: refused at its bracket, line 3 `  "version": [[…`, before anything is parsed.
  const std::string past = file + ": line 3, column 77: arrays and objects nested more than 64 deep, the limit";
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": " + nested(limit))) == past);
  // Objects are levels as arrays are, and an unfinished text is refused at the same bracket.
  std::string objects;
  for (std::size_t i = 0; i < limit; ++i) objects += "{\"a\":";
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": " + objects)).starts_with(file + ": line 3, "));
  // 200,000 levels once overflowed the stack (exit 139) when the message printed the value.
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", "\"version\": " + nested(200'000))) == past);
  // Brackets in strings are text, an escaped quote does not end its string, an escaped backslash
  // does not escape the quote after it.
  const std::string brackets = R"(\"[{)" + std::string(200, '[') + R"(\\)";
  writeAll(t.dir / "results.json", replaced(valid, "\"message\": \"\"", "\"message\": \"" + brackets + "\""));
  CHECK(readResults(t.dir, 64).frames.at(0).message == "\"[{" + std::string(200, '[') + "\\");
  CHECK(refusal(t.dir, replaced(valid, "\"version\": 1", R"("version": "\\", "x": )" + nested(limit))) ==
        file + ": line 3, column 88: arrays and objects nested more than 64 deep, the limit");
}

TEST_CASE("golden report: a megabyte of one value in results.json makes a message of a few hundred bytes") {
  TempDir t;
  const std::string valid = oneFrameJson(t.dir);
  const std::string file = (t.dir / "results.json").string();
  const std::string mb(1 << 20, 'x');
  const std::string cut = std::string(report::kMaxQuotedBytes - 3, 'x') + "…";
  struct Case {
    std::string from, to, message;
  };
  const Case cases[] = {
      {"\"version\": 1", "\"version\": \"" + mb + "\"",
       file + ": version: is \"" + cut + "\" (1048576 bytes), and this particles reads version 1"},
      {"\"outcome\": \"failed\"", "\"outcome\": \"" + mb + "\"",
       file + ": frames[0].outcome: unknown outcome \"" + cut +
           "\" (1048576 bytes) (passed, failed, missing or error)"},
      {"\"name\": \"a\"", "\"" + mb + "\": \"a\"",
       file + ": frames[0]: has an unknown key \"" + cut + "\" (1048576 bytes)"},
      {"\"threshold\": 16", "\"threshold\": \"" + mb + "\"", file + ": frames[0].numbers.threshold: is not an integer"},
      {"\"actual\": \"frames/a.png\"", "\"actual\": [\"" + mb + "\"]",
       file + ": frames[0].files.actual: is not a string"},
      // nlohmann's own message quotes the token it stopped in, here the rest of the file: cut.
      {"\"name\": \"a\"", "\"name\": \"" + mb + "\n",
       file +
           ": not JSON: parse error at line 24, column 0: syntax error while parsing value - invalid string: "
           "control character U+000A (LF) must be escaped to \\u000A or \\n; last read: '\"" +
           std::string(report::kMaxQuotedBytes - 4, 'x') + "…' (1048585 bytes)"},
      // A number past a double: nlohmann's out_of_range, once "internal error" and exit 1.
      {"\"threshold\": 16", "\"threshold\": 1" + std::string(1 << 20, '0'),
       file + ": line 30, column 1048599: number overflow parsing '1" + std::string(report::kMaxQuotedBytes - 4, '0') +
           "…' (1048577 bytes)"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.from);
    const std::string message = refusal(t.dir, replaced(valid, c.from, c.to));
    CHECK(message == c.message);
    CHECK(message.size() - file.size() < 300);  // the file's name is the caller's, the rest bounded
  }
}

TEST_CASE("golden report and update --from: results.json nested 200,000 deep is exit 2, and nothing is left behind") {
  particles::test::Scratch s;
  fs::create_directories(s.dir / "good" / "frames");
  fs::create_directories(s.dir / "deep");
  const std::string valid = oneFrameJson(s.dir / "good");
  writeAll(s.dir / "good" / "frames" / "a.png", "kept");  // merging copies it, unread
  fs::copy(s.dir / "good", s.dir / "twin", fs::copy_options::recursive);
  writeAll(s.dir / "deep" / "results.json", replaced(valid, "\"version\": 1", "\"version\": " + nested(200'000)));
  s.write("m.yaml", "references: refs\nframes:\n  - {scenario: s.yaml, times: [0.5]}\n");
  s.write("s.yaml", particles::test::kSwingScenario);
  const std::string before = listing(s.dir);
  const std::string deep =
      "error: deep/results.json: line 3, column 77: arrays and objects nested more than 64 deep, the limit\n";
  struct Row {
    std::string args, err;
  };
  const Row rows[] = {
      {"golden report deep -o merged", deep},
      {"golden report good deep -o merged", deep},
      {"golden update m.yaml --from deep", deep},
      {"golden update m.yaml --from good --from deep", deep},
      // Refused before any kept file is copied: the staging folder is removed.
      {"golden report good twin -o merged",
       "error: good and twin both hold a: merge the shards of one run, each once\n"},
  };
  for (const Row& row : rows) {
    CAPTURE(row.args);
    const particles::test::Result r = s.run(row.args);
    CHECK(r.code == 2);
    CHECK(r.err == row.err);
    CHECK(r.err.size() < 300);
    CHECK(listing(s.dir) == before);  // no merged/, no merged.partial-*, no refs/
  }
}

TEST_CASE("golden report: the fuzzer's dictionary has every key results.json is written with") {
  TempDir t;
  writeReport(t.dir, everyField());
  const std::string json = readAll(t.dir / "results.json");
  const std::string dict = readAll(fs::path(PARTICLES_SOURCE_DIR) / "tests/fuzz/results_json.dict");
  const std::regex key(R"re("([a-z_]+)": )re");
  std::size_t keys = 0;
  for (auto it = std::sregex_iterator(json.begin(), json.end(), key); it != std::sregex_iterator(); ++it, ++keys) {
    const std::string entry = "\"\\\"" + (*it)[1].str() + "\\\": \"\n";  // "\"name\": " in libFuzzer's syntax
    CHECK_MESSAGE(dict.find(entry) != std::string::npos, "tests/fuzz/results_json.dict has no " << entry);
  }
  CHECK(keys > 40);  // the regular expression finds them
}
