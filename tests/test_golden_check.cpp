// The frame check and the state check (golden/frame_check.hpp, golden/state_check.hpp) on a small
// pendulum: each outcome (passed, failed, missing, error, and an unusable reference), its message,
// the files kept for the report and the commands that reproduce it.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "golden/check.hpp"
#include "golden/check_context.hpp"
#include "golden/frame_check.hpp"
#include "golden/state_check.hpp"
#include "golden/state_table.hpp"
#include "render/image.hpp"
#include "render/png_io.hpp"
#include "scenario/golden_manifest.hpp"

namespace fs = std::filesystem;
using namespace particles;
using namespace particles::golden;
using scenario::GoldenCheck;
using scenario::GoldenManifest;
using test::kSwingScenario;
using test::Scratch;
using test::slurp;

namespace {

// A manifest in a folder of its own, its references in refs/, a report folder with frames/ and
// states/, and the checks' options as `golden check golden.yaml` has them.
class GoldenRun {
 public:
  explicit GoldenRun(const std::string& manifestYaml) : dir_(scratch_.dir) {
    scratch_.write("swing.yaml", kSwingScenario);
    fs::create_directories(dir_ / "refs");
    fs::create_directories(dir_ / "report/frames");
    fs::create_directories(dir_ / "report/states");
    manifest = scenario::loadGoldenManifestText("references: refs\n" + manifestYaml, "golden.yaml", dir_);
    options.manifestGiven = "golden.yaml";
  }
  const fs::path& dir() const { return dir_; }
  fs::path report() const { return dir_ / "report"; }
  fs::path refs() const { return dir_ / "refs"; }

  // Every frame of the manifest's first frame entry, checked afresh.
  std::vector<FrameResult> frames() {
    std::vector<GoldenCheck> checks;
    for (const GoldenCheck& c : scenario::goldenChecks(manifest)) {
      if (c.kind == GoldenCheck::Kind::frame && c.entry == 0) checks.push_back(c);
    }
    CheckContext run(manifest, report(), options, long(checks.size()));
    std::vector<FrameResult> results = checkFrames(run, checks);
    badReference = run.badReference();
    return results;
  }

  StateResult state() {
    const GoldenCheck check{GoldenCheck::Kind::state, 0, 0, manifest.states.at(0).stateName};
    CheckContext run(manifest, report(), options, 1);
    StateResult result = checkState(run, check);
    badReference = run.badReference();
    return result;
  }

  GoldenManifest manifest;
  CheckOptions options;
  bool badReference = false;

 private:
  Scratch scratch_;
  fs::path dir_;
};

}  // namespace

TEST_CASE("frame check: missing, passed, failed, a size that differs, an unusable reference, errors") {
  GoldenRun g("frames:\n  - {scenario: swing.yaml, times: [0.5, 2]}\n");
  const std::string shownRefs = (g.refs()).lexically_normal().string();
  const std::string render = "particles render " + (g.dir() / "swing.yaml").lexically_normal().string() +
                             " -o swing_t0.5.png --at 0.5 --size 160x120 --msaa 4 --theme dark";
  const std::string check = "particles golden check golden.yaml --only swing_t0.5";

  std::vector<FrameResult> r = g.frames();
  REQUIRE(r.size() == 2);
  CHECK(r[0].name == "swing_t0.5");
  CHECK(r[0].outcome == Outcome::missing);
  CHECK(r[0].message == "no reference " + shownRefs +
                            "/swing_t0.5.png yet: create it with particles golden "
                            "update golden.yaml --missing");
  CHECK(r[0].files.actual == "frames/swing_t0.5.actual.png");
  CHECK(r[0].reproduce == std::vector<std::string>{render, check});
  CHECK(r[1].outcome == Outcome::error);
  CHECK(r[1].message == "t = 2 s is after the scenario's duration, 1 s");
  CHECK(r[1].files.actual.empty());
  CHECK_FALSE(g.badReference);
  const render::Image actual = render::readPng(g.report() / r[0].files.actual);
  CHECK(actual.width == 160);
  CHECK(actual.height == 120);

  // Its own frame as the reference: passed, nothing kept.
  fs::copy_file(g.report() / r[0].files.actual, g.refs() / "swing_t0.5.png");
  fs::remove(g.report() / r[0].files.actual);
  r = g.frames();
  CHECK(r[0].outcome == Outcome::passed);
  CHECK(r[0].message.empty());
  REQUIRE(r[0].numbers);
  CHECK(r[0].numbers->differing == 0);
  CHECK(r[0].numbers->pixels == 160 * 120);
  CHECK(r[0].files.actual.empty());
  CHECK(r[0].reproduce == std::vector<std::string>{render,
                                                   "particles compare " + shownRefs +
                                                       "/swing_t0.5.png swing_t0.5.png --threshold 16 --max-share "
                                                       "0.0002 --diff swing_t0.5.diff.png",
                                                   check});
  CHECK_FALSE(fs::exists(g.report() / "frames/swing_t0.5.actual.png"));

  // A reference with its left half inverted: failed, actual, expected and diff kept.
  render::Image changed = actual;
  for (int y = 0; y < changed.height; ++y) {
    for (int x = 0; x < changed.width / 2; ++x) {
      for (int c = 0; c < 3; ++c) changed.pixel(x, y)[c] = std::uint8_t(255 - changed.pixel(x, y)[c]);
    }
  }
  render::writePng(g.refs() / "swing_t0.5.png", changed);
  r = g.frames();
  CHECK(r[0].outcome == Outcome::failed);
  CHECK(r[0].message.find("% of the pixels differ by more than 16 (") != std::string::npos);
  CHECK(r[0].files.actual == "frames/swing_t0.5.actual.png");
  CHECK(r[0].files.expected == "frames/swing_t0.5.expected.png");
  CHECK(r[0].files.diff == "frames/swing_t0.5.diff.png");
  CHECK(render::readPng(g.report() / r[0].files.expected) == changed);
  CHECK(render::readPng(g.report() / r[0].files.actual) == actual);

  // A reference of another size: failed without comparing pixels.
  render::writePng(g.refs() / "swing_t0.5.png", render::Image(4, 4));
  r = g.frames();
  CHECK(r[0].outcome == Outcome::failed);
  CHECK(r[0].message.rfind("the frame and its reference differ in size: ", 0) == 0);
  CHECK_FALSE(r[0].numbers);
  CHECK(r[0].files.diff.empty());

  // A reference that is no PNG: the check's error, and bad input for the run.
  std::ofstream(g.refs() / "swing_t0.5.png", std::ios::trunc) << "not a PNG";
  r = g.frames();
  CHECK(r[0].outcome == Outcome::error);
  CHECK(r[0].message.rfind("the reference cannot be used: ", 0) == 0);
  CHECK(g.badReference);

  // A scenario that does not load: every frame of the entry is an error, with the loader's message.
  fs::remove(g.dir() / "swing.yaml");
  r = g.frames();
  for (const FrameResult& f : r) {
    CHECK(f.outcome == Outcome::error);
    CHECK(f.message.find("swing.yaml") != std::string::npos);
    CHECK(f.reproduce == std::vector<std::string>{"particles golden check golden.yaml --only " + f.name});
  }
}

TEST_CASE("frame check with --gpu: drawn on a GPU, or an error that says there is none, and --gpu in the commands") {
  // golden check --gpu: the GPU's raster path against the references (golden/README.md, "On a
  // GPU"). Where EGL lists no hardware device (CI, this project's development machine) each frame
  // is an error with render's message; on a GPU server the frame is drawn. Either way the command
  // that reproduces it asks for the GPU.
  GoldenRun g("frames:\n  - {scenario: swing.yaml, times: [0.5]}\n");
  g.options.gl.backend = render::GlBackend::egl;
  g.options.gl.gpu = true;
  const std::vector<FrameResult> r = g.frames();
  REQUIRE(r.size() == 1);
  if (r[0].outcome == Outcome::error) {
    CHECK(r[0].message.find("a GPU was asked for") != std::string::npos);
    CHECK(r[0].message.find("MiB held") == std::string::npos);  // not a memory problem
  } else {
    CHECK(r[0].outcome == Outcome::missing);
    REQUIRE_FALSE(r[0].reproduce.empty());
    CHECK(r[0].reproduce[0].find(" --gl egl --gpu") != std::string::npos);
  }
  CHECK(r[0].reproduce.back() == "particles golden check golden.yaml --only swing_t0.5 --gl egl --gpu");
  // The run says so among its settings over the manifest's, which golden update --from sets aside.
  g.options.overrides.maxShare = 0.001;
  const CheckRun run = runCheck(g.manifest, g.dir() / "gpu-report", g.options);
  REQUIRE(run.results.runs.size() == 1);
  CHECK(run.results.runs[0].overrides == "--max-share 0.001 --gpu");
}

TEST_CASE("frame check: a control that must differ passes when it differs, fails when it matches") {
  GoldenRun g(
      "frames:\n"
      "  - {scenario: swing.yaml, times: [0.5]}\n"
      "  - {scenario: swing.yaml, times: [0.5], name: control, expect: differ, reference: swing_t0.5}\n");
  g.options.keepAll = true;  // as `golden update`: the actual frame of every check
  std::vector<FrameResult> r = g.frames();
  REQUIRE(r.size() == 1);  // the first entry's: frames() checks one entry
  fs::copy_file(g.report() / r[0].files.actual, g.refs() / "swing_t0.5.png");

  std::swap(g.manifest.frames[0], g.manifest.frames[1]);  // the control as the first entry
  r = g.frames();
  REQUIRE(r.size() == 1);
  CHECK(r[0].name == "control");
  CHECK(r[0].outcome == Outcome::failed);
  CHECK(r[0].message.rfind("a control that must differ matches its reference (0 pixels of 19200 differ", 0) == 0);

  g.manifest.frames[0].sets = {{"particles[1].pos", "[0.5, -0.8]"}};
  g.manifest.frames[0].setsAt = {{}};
  r = g.frames();
  CHECK(r[0].outcome == Outcome::passed);
  CHECK(r[0].files.diff == "frames/control.diff.png");  // what the comparison saw
  CHECK(r[0].files.expected.empty());
}

TEST_CASE("state check: missing, passed, failed, an unusable reference, errors") {
  GoldenRun g("states:\n  - {scenario: swing.yaml, times: [0.25, 0.5]}\n");
  const std::string shownRef = (g.refs() / "swing.csv").lexically_normal().string();

  StateResult r = g.state();
  CHECK(r.name == "swing");
  CHECK(r.times == std::vector<std::string>{"0.25", "0.5"});
  CHECK(r.outcome == Outcome::missing);
  CHECK(r.message == "no reference " + shownRef + " yet: create it with particles golden update golden.yaml --missing");
  CHECK(r.files.actual == "states/swing.actual.csv");
  CHECK(r.reproduce == std::vector<std::string>{"particles golden check golden.yaml --only swing"});
  const std::string actualText = slurp(g.report() / r.files.actual);
  const std::vector<StateRow> rows = parseStateText(actualText, "actual");
  REQUIRE(rows.size() == 4);  // two points at two times

  fs::copy_file(g.report() / r.files.actual, g.refs() / "swing.csv");
  fs::remove(g.report() / r.files.actual);
  r = g.state();
  CHECK(r.outcome == Outcome::passed);
  CHECK(r.values == 24);
  CHECK(r.files.actual.empty());
  CHECK_FALSE(fs::exists(g.report() / "states/swing.actual.csv"));

  // The bob 1 mm off at 0.5 s: beyond the default 1e-6 m.
  std::vector<StateRow> moved = rows;
  moved[3].values[0] += 1e-3;
  std::ofstream(g.refs() / "swing.csv", std::ios::trunc) << stateText(moved);
  r = g.state();
  CHECK(r.outcome == Outcome::failed);
  CHECK(r.message.rfind("at t = 0.5, bob x is ", 0) == 0);
  CHECK(r.message.find("beyond 1e-06") != std::string::npos);
  REQUIRE(r.firstBeyond);
  CHECK(r.firstBeyond->point == "bob");
  CHECK(r.files.actual == "states/swing.actual.csv");
  CHECK(r.files.expected == "states/swing.expected.csv");
  CHECK(slurp(g.report() / r.files.expected) == stateText(moved));
  CHECK(slurp(g.report() / r.files.actual) == actualText);

  // Widened to 1 cm by the manifest's default, the same reference passes.
  g.manifest.defaultStateTolerance.position = scenario::GoldenSetting<double>{0.01, {}};
  CHECK(g.state().outcome == Outcome::passed);

  std::ofstream(g.refs() / "swing.csv", std::ios::trunc) << "t,name\n";
  r = g.state();
  CHECK(r.outcome == Outcome::error);
  CHECK(r.message.rfind("the reference cannot be used: ", 0) == 0);
  CHECK(g.badReference);

  g.manifest.states[0].times.push_back({2.0, "2", "", {}});
  r = g.state();
  CHECK(r.outcome == Outcome::error);
  CHECK(r.message == "t = 2 s is after the scenario's duration, 1 s");
  CHECK_FALSE(g.badReference);
}

TEST_CASE("golden run: entries on a pool of threads give one thread's results, in manifest order") {
  GoldenRun g(
      "frames:\n"
      "  - {scenario: swing.yaml, times: [0.5], name: a}\n"
      "  - {scenario: swing.yaml, times: [0.25, 0.75], set: {\"particles[1].pos\": [0.5, -0.8]}}\n"
      "states:\n"
      "  - {scenario: swing.yaml, times: [0.5], name: s1}\n"
      "  - {scenario: swing.yaml, times: [1], name: s2}\n"
      "  - {scenario: swing.yaml, times: [3], name: late}\n");
  auto runWith = [&](int jobs, const std::string& folder) {
    g.options.jobs = jobs;
    long calls = 0;
    g.options.progress = [&](long done, long total, const std::string&) {
      ++calls;
      CHECK(done == calls);
      CHECK(total == 6);
    };
    CheckRun run = runCheck(g.manifest, g.dir() / folder, g.options);
    CHECK(calls == 6);
    return run;
  };
  const CheckRun one = runWith(1, "one");
  const CheckRun pooled = runWith(4, "pooled");
  auto namesOf = [](const auto& results) {
    std::vector<std::string> names;
    for (const auto& r : results) names.push_back(r.name);
    return names;
  };
  CHECK(namesOf(pooled.results.frames) == std::vector<std::string>{"a", "swing_t0.25", "swing_t0.75"});
  CHECK(namesOf(pooled.results.states) == std::vector<std::string>{"s1", "s2", "late"});
  for (size_t i = 0; i < one.results.frames.size(); ++i) {
    const FrameResult &a = one.results.frames[i], &b = pooled.results.frames[i];
    CAPTURE(a.name);
    CHECK(b.outcome == Outcome::missing);
    CHECK(b.message == a.message);
    CHECK(b.reproduce == a.reproduce);
    CHECK(slurp(g.dir() / "pooled" / b.files.actual) == slurp(g.dir() / "one" / a.files.actual));
  }
  for (size_t i = 0; i < one.results.states.size(); ++i) {
    const StateResult &a = one.results.states[i], &b = pooled.results.states[i];
    CAPTURE(a.name);
    CHECK(b.outcome == a.outcome);
    CHECK(b.message == a.message);
    if (!a.files.actual.empty()) {
      CHECK(slurp(g.dir() / "pooled" / b.files.actual) == slurp(g.dir() / "one" / a.files.actual));
    }
  }
  CHECK(pooled.results.states[2].outcome == Outcome::error);
  CHECK(pooled.results.runs.at(0).gl == one.results.runs.at(0).gl);
  CHECK_FALSE(pooled.results.runs.at(0).gl.empty());
}
