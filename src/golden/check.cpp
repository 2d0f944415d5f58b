// Checking a golden manifest: see check.hpp.
#include "golden/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <new>
#include <stdexcept>
#include <thread>

#include "core/solver.hpp"
#include "golden/state_table.hpp"
#include "input/closest_name.hpp"
#include "input/text_file.hpp"
#include "output/output_file.hpp"
#include "output/shell_words.hpp"
#include "render/image_compare.hpp"
#include "render/png_io.hpp"
#include "render/renderer.hpp"
#include "scenario/scenario.hpp"

namespace particles::golden {

namespace fs = std::filesystem;
using output::shellCommand;
using scenario::GoldenEntry;
using scenario::GoldenManifest;

namespace {

// One check the options selected: a frame (entry, time) or a state (entry).
struct Check {
  bool frame = true;
  size_t entry = 0, time = 0;
  std::string name;
  size_t slot = 0;  // its index among the selected, frames first
};

// A state tolerance not given anywhere: see golden/README.md, "States", for how they were chosen.
constexpr StateTolerance kDefaultStateTolerance{1e-6, 1e-5, 1e-6, 1e-5};

double since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A path as the commands that reproduce a result write it: relative to where the check runs.
std::string shownPath(const fs::path& p) {
  return p.lexically_normal().string();
}

// The render settings of an entry: its own, over the manifest's defaults, over the command line's
// overrides of the defaults, over the scenario's size and the program's defaults.
struct Look {
  render::RenderOptions options;
  std::vector<std::string> args;  // as `particles render` takes them
};

template <class T>
const std::optional<scenario::GoldenSetting<T>>& pick(const std::optional<scenario::GoldenSetting<T>>& own,
                                                      const std::optional<scenario::GoldenSetting<T>>& fallback) {
  return own ? own : fallback;
}

Look lookOf(const GoldenManifest& m, const GoldenEntry& e, const scenario::Scenario& s, const CheckOverrides& o) {
  Look look;
  render::RenderOptions& r = look.options;
  r.width = s.render.width;
  r.height = s.render.height;
  if (const auto& size = pick(e.render.size, m.defaultRender.size)) {
    r.width = size->value.first;
    r.height = size->value.second;
  }
  if (const auto& msaa = pick(e.render.msaa, m.defaultRender.msaa)) r.msaa = msaa->value;
  if (const auto& theme = pick(e.render.theme, m.defaultRender.theme))
    r.themeName = *render::themeFromName(theme->value);
  if (const auto& bg = pick(e.render.background, m.defaultRender.background)) {
    r.transparentBackground = bg->value == "transparent";
  }
  if (e.render.raster) {
    r.raster = *render::rasterFromName(e.render.raster->value);
  } else if (o.raster) {
    r.raster = *o.raster;
  } else if (m.defaultRender.raster) {
    r.raster = *render::rasterFromName(m.defaultRender.raster->value);
  }
  look.args = {"--size",  fmt::format("{}x{}", r.width, r.height),      "--msaa", fmt::format("{}", r.msaa),
               "--theme", std::string(render::themeNameOf(r.themeName))};
  if (r.transparentBackground) look.args.insert(look.args.end(), {"--background", "transparent"});
  if (r.raster != render::Raster::automatic) {
    look.args.insert(look.args.end(), {"--raster", std::string(render::rasterNameOf(r.raster))});
  }
  return look;
}

render::CompareTolerance toleranceOf(const GoldenManifest& m, const GoldenEntry& e, const CheckOverrides& o) {
  render::CompareTolerance t;
  if (e.tolerance.threshold) {
    t.threshold = e.tolerance.threshold->value;
  } else if (o.threshold) {
    t.threshold = *o.threshold;
  } else if (m.defaultTolerance.threshold) {
    t.threshold = m.defaultTolerance.threshold->value;
  }
  if (e.tolerance.maxShare) {
    t.maxShare = e.tolerance.maxShare->value;
  } else if (o.maxShare) {
    t.maxShare = *o.maxShare;
  } else if (m.defaultTolerance.maxShare) {
    t.maxShare = m.defaultTolerance.maxShare->value;
  }
  return t;
}

StateTolerance stateToleranceOf(const GoldenManifest& m, const GoldenEntry& e) {
  StateTolerance t = kDefaultStateTolerance;
  auto set = [](double& to, const auto& own, const auto& fallback) {
    if (const auto& v = pick(own, fallback)) to = v->value;
  };
  set(t.position, e.stateTolerance.position, m.defaultStateTolerance.position);
  set(t.velocity, e.stateTolerance.velocity, m.defaultStateTolerance.velocity);
  set(t.angle, e.stateTolerance.angle, m.defaultStateTolerance.angle);
  set(t.omega, e.stateTolerance.omega, m.defaultStateTolerance.omega);
  return t;
}

std::vector<scenario::Override> overridesOf(const GoldenManifest& m, const GoldenEntry& e) {
  std::vector<scenario::Override> out;
  for (size_t i = 0; i < e.sets.size(); ++i) {
    const scenario::GoldenPosition& at = e.setsAt[i];
    out.push_back({e.sets[i].first, e.sets[i].second, fmt::format("{}:{}:{}, set", m.file, at.line, at.column)});
  }
  return out;
}

std::vector<std::string> setArgs(const GoldenEntry& e) {
  std::vector<std::string> args;
  for (const auto& [path, value] : e.sets) args.insert(args.end(), {"--set", path + "=" + value});
  return args;
}

// A reference read within the limits and never waited on: a regular file, or an error.
struct ReferenceError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string readReference(const fs::path& file, std::uintmax_t maxInputMiB) {
  try {
    return input::readBinaryFile(file, maxInputMiB, input::Accept::regularOnly);
  } catch (const input::ReadError& e) {
    throw ReferenceError(fmt::format("reference {}: {}", shownPath(file), e.what()));
  }
}

bool referenceAbsent(const fs::path& file) {
  std::error_code ec;
  return fs::symlink_status(file, ec).type() == fs::file_type::not_found;
}

void writeText(const fs::path& file, const std::string& text) {
  output::OutputFile out(file);
  out.write(text);
  out.commit();
}

// What the threads share: the manifest, the options, the selected checks and their result slots.
class CheckRunner {
 public:
  CheckRunner(const GoldenManifest& manifest, const fs::path& folder, const CheckOptions& options,
              std::vector<Check> checks)
      : m_(manifest), folder_(folder), o_(options), checks_(std::move(checks)) {
    for (const Check& c : checks_) (c.frame ? frameCount_ : stateCount_) += 1;
    frames_.resize(frameCount_);
    states_.resize(stateCount_);
  }

  CheckRun run() {
    // Units: the selected checks of one entry, simulated together.
    std::vector<std::vector<const Check*>> units;
    for (const Check& c : checks_) {
      if (units.empty() || units.back().front()->frame != c.frame || units.back().front()->entry != c.entry) {
        units.emplace_back();
      }
      units.back().push_back(&c);
    }
    std::atomic<size_t> next{0};
    auto work = [&] {
      for (size_t u; (u = next++) < units.size();) runUnit(units[u]);
    };
    const size_t threads = std::min(units.size(), size_t(std::max(1, o_.jobs)));
    if (threads <= 1) {
      work();
    } else {
      std::vector<std::jthread> pool;
      for (size_t i = 0; i < threads; ++i) pool.emplace_back(work);
    }
    if (firstFailure_) std::rethrow_exception(firstFailure_);
    CheckRun out;
    out.results.frames = std::move(frames_);
    out.results.states = std::move(states_);
    out.badReference = badReference_;
    RunFacts facts;
    facts.gl = gl_;
    facts.overrides = o_.overrides.text();
    if (o_.shard) facts.shard = fmt::format("{}/{}", o_.shard->first, o_.shard->second);
    out.results.runs.push_back(facts);
    return out;
  }

 private:
  void runUnit(const std::vector<const Check*>& unit) {
    try {
      if (unit.front()->frame) {
        runFrames(unit);
      } else {
        runState(*unit.front());
      }
    } catch (const output::OutputError&) {  // the report folder: the run's failure, not the entry's
      std::lock_guard lock(mutex_);
      if (!firstFailure_) firstFailure_ = std::current_exception();
    } catch (const std::bad_alloc&) {
      std::lock_guard lock(mutex_);
      if (!firstFailure_) firstFailure_ = std::current_exception();
    }
  }

  void done(const std::string& name) {
    std::lock_guard lock(mutex_);
    ++done_;
    if (o_.progress) o_.progress(done_, long(checks_.size()), name);
  }

  std::vector<std::string> checkCommand(const std::string& name) const {
    std::vector<std::string> args = {o_.program, "golden", "check", o_.manifestGiven, "--only", name};
    const std::vector<std::string> overrides = o_.overrides.args();
    args.insert(args.end(), overrides.begin(), overrides.end());
    if (o_.gl.backend != render::GlBackend::automatic) {
      args.insert(args.end(), {"--gl", std::string(render::glBackendName(o_.gl.backend))});
    }
    return args;
  }

  void noteGl(const render::GlInfo& info) {
    std::lock_guard lock(mutex_);
    if (gl_.empty()) gl_ = render::describe(info);
  }

  void runFrames(const std::vector<const Check*>& unit) {
    const GoldenEntry& e = m_.frames[unit.front()->entry];
    auto start = std::chrono::steady_clock::now();
    std::vector<FrameResult*> results;
    for (const Check* c : unit) {
      FrameResult& r = frames_[c->slot];
      const scenario::GoldenTime& t = e.times[c->time];
      r.name = c->name;
      r.scenario = e.scenarioGiven;
      r.time = t.text;
      r.expectDiffer = e.expectDiffer;
      r.reference = shownPath(frameReference(m_, e.reference ? e.reference->value : c->name));
      r.reproduce.push_back(shellCommand(checkCommand(c->name)));
      results.push_back(&r);
    }
    size_t next = 0;  // the first check without an outcome
    auto finish = [&](FrameResult& r) {
      r.seconds = since(start);
      start = std::chrono::steady_clock::now();
      ++next;
      done(r.name);
    };
    auto failRest = [&](const std::string& message) {
      while (next < results.size()) {
        results[next]->outcome = Outcome::error;
        results[next]->message = message;
        finish(*results[next]);
      }
    };
    try {
      const std::vector<scenario::Override> sets = overridesOf(m_, e);
      scenario::Scenario s = scenario::loadScenarioFile(e.scenario, sets, o_.maxInputMiB);
      const Look look = lookOf(m_, e, s, o_.overrides);
      render::validate(look.options);
      const render::CompareTolerance tolerance = toleranceOf(m_, e, o_.overrides);
      render::Renderer renderer(look.options, o_.gl);
      noteGl(renderer.gl());
      const render::Camera camera{s.render.viewCenter, s.render.viewHeight};
      Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
      render::PngOptions png;
      png.alpha = look.options.transparentBackground;
      for (const Check* c : unit) {
        const scenario::GoldenTime& t = e.times[c->time];
        FrameResult& r = *results[next];
        std::vector<std::string> renderArgs = {o_.program, "render", shownPath(e.scenario), "-o", r.name + ".png",
                                               "--at",     t.text};
        renderArgs.insert(renderArgs.end(), look.args.begin(), look.args.end());
        const std::vector<std::string> sets = setArgs(e);
        renderArgs.insert(renderArgs.end(), sets.begin(), sets.end());
        if (o_.gl.backend != render::GlBackend::automatic) {
          renderArgs.insert(renderArgs.end(), {"--gl", std::string(render::glBackendName(o_.gl.backend))});
        }
        r.reproduce.insert(r.reproduce.begin(), shellCommand(renderArgs));
        if (t.seconds > s.simulation.duration + 1e-9) {
          r.outcome = Outcome::error;
          r.message = fmt::format("t = {} s is after the scenario's duration, {} s", t.text, s.simulation.duration);
          finish(r);
          continue;
        }
        if (t.seconds > s.system.time()) stepper.advanceTo(t.seconds);
        const render::Image actual = renderer.render(s.system.draw(), camera);
        compareFrame(e, r, actual, tolerance, png);
        finish(r);
      }
    } catch (const output::OutputError&) {
      throw;
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& ex) {  // the scenario, the simulation, the renderer
      failRest(ex.what());
    }
  }

  // A reference that cannot be used (not a regular file, too large, not a PNG or state file): the
  // check's error, and bad input for the run's exit code.
  template <class Result>
  void unusableReference(Result& r, const std::exception& why) {
    r.outcome = Outcome::error;
    r.message = fmt::format("the reference cannot be used: {}", why.what());
    std::lock_guard lock(mutex_);
    badReference_ = true;
  }

  void keep(const fs::path& relative, const render::Image& image, const render::PngOptions& png) {
    render::writePng(folder_ / relative, image, png);
  }

  void compareFrame(const GoldenEntry& e, FrameResult& r, const render::Image& actual,
                    const render::CompareTolerance& tolerance, const render::PngOptions& png) {
    const fs::path reference = r.reference;
    const std::string actualFile = "frames/" + r.name + ".actual.png";
    const std::string expectedFile = "frames/" + r.name + ".expected.png";
    const std::string diffFile = "frames/" + r.name + ".diff.png";
    if (o_.keepAll) {
      keep(actualFile, actual, png);
      r.files.actual = actualFile;
    }
    if (referenceAbsent(reference)) {
      r.outcome = Outcome::missing;
      r.message = e.reference
                      ? fmt::format(
                            "no reference {} yet: this check compares with frame {}'s reference, which "
                            "`golden update` writes for the manifest that has frame {}",
                            shownPath(reference), e.reference->value, e.reference->value)
                      : fmt::format("no reference {} yet: create it with {}", shownPath(reference),
                                    shellCommand({o_.program, "golden", "update", o_.manifestGiven, "--missing"}));
      if (!o_.keepAll) keep(actualFile, actual, png);
      r.files.actual = actualFile;
      return;
    }
    // The reference's header first: a size other than the frame's is a failure told without
    // decoding its pixels (a header may claim 16384² pixels, 1 GiB).
    std::string bytes;
    render::Image expected;
    std::string mismatch;
    try {
      bytes = readReference(reference, o_.maxInputMiB);
      const std::span<const std::uint8_t> pngBytes(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      const render::PngSize size = render::readPngBytesSize(pngBytes, r.reference);
      mismatch = render::sizeMismatch(size.width, size.height, actual.width, actual.height);
      if (mismatch.empty()) expected = render::readPngBytes(pngBytes, r.reference);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& ex) {
      unusableReference(r, ex);
      return;
    }
    r.reproduce.insert(r.reproduce.begin() + 1,
                       shellCommand({o_.program, "compare", r.reference, r.name + ".png", "--threshold",
                                     fmt::format("{}", tolerance.threshold), "--max-share",
                                     fmt::format("{}", tolerance.maxShare), "--diff", r.name + ".diff.png"}));
    if (!mismatch.empty()) {
      r.outcome = Outcome::failed;
      r.message = fmt::format("the frame and its reference differ in size: {}", mismatch);
      if (!o_.keepAll) keep(actualFile, actual, png);
      r.files.actual = actualFile;
      writeText(folder_ / expectedFile, bytes);
      r.files.expected = expectedFile;
      return;
    }
    const render::ImageComparison c = render::compareImages(expected, actual, tolerance);
    r.numbers = frameNumbersOf(c, tolerance);
    const bool differs = !c.passed;
    r.outcome = differs == r.expectDiffer ? Outcome::passed : Outcome::failed;
    if (r.outcome == Outcome::failed) {
      r.message =
          r.expectDiffer
              ? fmt::format(
                    "a control that must differ matches its reference ({} pixels of {} "
                    "differ; the bound is {:.4g} %): the check cannot see this change",
                    c.differing, c.pixels, 100.0 * tolerance.maxShare)
              : fmt::format("{:.4f} % of the pixels differ by more than {} ({} of {}; bound {:.4g} %)", 100.0 * c.share,
                            tolerance.threshold, c.differing, c.pixels, 100.0 * tolerance.maxShare);
    }
    if (r.outcome == Outcome::failed || r.expectDiffer) {
      if (!o_.keepAll) keep(actualFile, actual, png);
      r.files.actual = actualFile;
      keep(diffFile, render::diffImage(expected, actual, tolerance.threshold), {});
      r.files.diff = diffFile;
      if (r.outcome == Outcome::failed) {
        writeText(folder_ / expectedFile, bytes);
        r.files.expected = expectedFile;
      }
    }
  }

  void runState(const Check& check) {
    const GoldenEntry& e = m_.states[check.entry];
    const auto start = std::chrono::steady_clock::now();
    StateResult& r = states_[check.slot];
    r.name = check.name;
    r.scenario = e.scenarioGiven;
    for (const scenario::GoldenTime& t : e.times) r.times.push_back(t.text);
    const fs::path reference = stateReference(m_, r.name);
    r.reference = shownPath(reference);
    r.reproduce.push_back(shellCommand(checkCommand(r.name)));
    auto finish = [&] {
      r.seconds = since(start);
      done(r.name);
    };
    std::vector<StateRow> actual;
    try {
      const std::vector<scenario::Override> sets = overridesOf(m_, e);
      scenario::Scenario s = scenario::loadScenarioFile(e.scenario, sets, o_.maxInputMiB);
      Stepper stepper(s.system, s.simulation.integrator, s.simulation.dt);
      for (const scenario::GoldenTime& t : e.times) {
        if (t.seconds > s.simulation.duration + 1e-9) {
          throw std::invalid_argument(
              fmt::format("t = {} s is after the scenario's duration, {} s", t.text, s.simulation.duration));
        }
        if (t.seconds > s.system.time()) stepper.advanceTo(t.seconds);
        std::vector<StateRow> rows = stateRows(s.system, t.text);
        actual.insert(actual.end(), std::make_move_iterator(rows.begin()), std::make_move_iterator(rows.end()));
      }
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& ex) {
      r.outcome = Outcome::error;
      r.message = ex.what();
      finish();
      return;
    }
    const std::string actualText = stateText(actual);
    const std::string actualFile = "states/" + r.name + ".actual.csv";
    const std::string expectedFile = "states/" + r.name + ".expected.csv";
    auto keepActual = [&] {
      writeText(folder_ / actualFile, actualText);
      r.files.actual = actualFile;
    };
    if (o_.keepAll) keepActual();
    if (referenceAbsent(reference)) {
      r.outcome = Outcome::missing;
      r.message = fmt::format("no reference {} yet: create it with {}", r.reference,
                              shellCommand({o_.program, "golden", "update", o_.manifestGiven, "--missing"}));
      if (!o_.keepAll) keepActual();
      finish();
      return;
    }
    std::string expectedText;
    std::vector<StateRow> expected;
    try {
      expectedText = readReference(reference, o_.maxInputMiB);
      expected = parseStateText(expectedText, r.reference);
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& ex) {
      unusableReference(r, ex);
      finish();
      return;
    }
    const StateComparison c = compareStates(expected, actual, stateToleranceOf(m_, e));
    r.values = c.values;
    r.firstBeyond = c.firstBeyond;
    r.largest = c.largest;
    r.outcome = c.passed ? Outcome::passed : Outcome::failed;
    if (!c.mismatch.empty()) {
      r.message = c.mismatch;
    } else if (c.firstBeyond) {
      const StateDeviation& d = *c.firstBeyond;
      r.message = fmt::format("at t = {}, {} {} is {} where the reference has {}: {:.3g} apart, beyond {:.3g}", d.time,
                              d.point, d.quantity, d.actual, d.expected, d.difference, d.tolerance);
    }
    if (!c.passed) {
      if (!o_.keepAll) keepActual();
      writeText(folder_ / expectedFile, expectedText);
      r.files.expected = expectedFile;
    }
    finish();
  }

  const GoldenManifest& m_;
  const fs::path folder_;
  const CheckOptions& o_;
  const std::vector<Check> checks_;
  size_t frameCount_ = 0, stateCount_ = 0;
  std::vector<FrameResult> frames_;
  std::vector<StateResult> states_;
  std::mutex mutex_;
  long done_ = 0;
  bool badReference_ = false;
  std::string gl_;
  std::exception_ptr firstFailure_;
};

}  // namespace

FrameNumbers frameNumbersOf(const render::ImageComparison& c, const render::CompareTolerance& tolerance) {
  FrameNumbers n;
  n.threshold = tolerance.threshold;
  n.maxShare = tolerance.maxShare;
  n.differing = c.differing;
  n.pixels = c.pixels;
  n.share = c.share;
  n.largest = c.largestDifference;
  if (c.box) n.box = std::array<int, 4>{c.box->x0, c.box->y0, c.box->x1, c.box->y1};
  n.width = c.width;
  n.height = c.height;
  return n;
}

std::vector<std::string> CheckOverrides::args() const {
  std::vector<std::string> words;
  if (raster) words.insert(words.end(), {"--raster", std::string(render::rasterNameOf(*raster))});
  if (threshold) words.insert(words.end(), {"--threshold", fmt::format("{}", *threshold)});
  if (maxShare) words.insert(words.end(), {"--max-share", fmt::format("{}", *maxShare)});
  return words;
}

std::string CheckOverrides::text() const {
  return fmt::format("{}", fmt::join(args(), " "));
}

fs::path frameReference(const GoldenManifest& manifest, const std::string& name) {
  return manifest.references / (name + ".png");
}

fs::path stateReference(const GoldenManifest& manifest, const std::string& name) {
  return manifest.references / (name + ".csv");
}

std::vector<std::string> checkNames(const GoldenManifest& manifest) {
  std::vector<std::string> names;
  for (const GoldenEntry& e : manifest.frames) {
    for (const scenario::GoldenTime& t : e.times) names.push_back(t.frameName);
  }
  for (const GoldenEntry& e : manifest.states) names.push_back(e.stateName);
  return names;
}

void checkRenderSettings(const GoldenManifest& manifest) {
  auto check = [&](const scenario::GoldenRenderSettings& r) {
    if (r.theme && !render::themeFromName(r.theme->value)) {
      scenario::failInManifest(
          manifest, r.theme->at,
          fmt::format("expected {}, got '{}'", fmt::join(render::kThemeNames, " or "), r.theme->value));
    }
    if (r.raster && !render::rasterFromName(r.raster->value)) {
      scenario::failInManifest(
          manifest, r.raster->at,
          fmt::format("expected {}, got '{}'", fmt::join(render::kRasterNames, ", "), r.raster->value));
    }
    if (r.background && r.background->value != "theme" && r.background->value != "transparent") {
      scenario::failInManifest(manifest, r.background->at,
                               fmt::format("expected theme or transparent, got '{}'", r.background->value));
    }
  };
  check(manifest.defaultRender);
  for (const GoldenEntry& e : manifest.frames) check(e.render);
}

CheckRun runCheck(const GoldenManifest& manifest, const fs::path& folder, const CheckOptions& options) {
  checkRenderSettings(manifest);
  const std::vector<std::string> all = checkNames(manifest);
  for (const std::string& name : options.only) {
    if (std::find(all.begin(), all.end(), name) == all.end()) {
      const std::string closest = input::closestName(name, all);
      throw std::invalid_argument(fmt::format("no frame or state of the manifest is named '{}'{}", name,
                                              closest.empty() ? "" : fmt::format("; did you mean {}?", closest)));
    }
  }
  std::vector<Check> selected;
  auto consider = [&](Check c, const fs::path& reference) {
    if (!options.only.empty() && std::find(options.only.begin(), options.only.end(), c.name) == options.only.end()) {
      return;
    }
    if (options.missingOnly && ((c.frame && manifest.frames[c.entry].reference) || !referenceAbsent(reference))) return;
    selected.push_back(std::move(c));
  };
  for (size_t i = 0; i < manifest.frames.size(); ++i) {
    for (size_t t = 0; t < manifest.frames[i].times.size(); ++t) {
      const std::string& name = manifest.frames[i].times[t].frameName;
      consider({true, i, t, name}, frameReference(manifest, name));
    }
  }
  for (size_t i = 0; i < manifest.states.size(); ++i) {
    consider({false, i, 0, manifest.states[i].stateName}, stateReference(manifest, manifest.states[i].stateName));
  }
  if (options.shard) {
    const auto [k, n] = *options.shard;
    if (n < 1 || k < 1 || k > n)
      throw std::invalid_argument(fmt::format("--shard {}/{}: expected K/N with 1 ≤ K ≤ N", k, n));
    // Contiguous blocks keep an entry's times together: most entries are simulated in one shard.
    const size_t total = selected.size();
    const size_t begin = total * size_t(k - 1) / size_t(n), end = total * size_t(k) / size_t(n);
    selected = std::vector<Check>(selected.begin() + long(begin), selected.begin() + long(end));
  }
  size_t frames = 0, states = 0;
  for (Check& c : selected) c.slot = c.frame ? frames++ : states++;
  std::error_code ec;
  fs::create_directories(folder / "frames", ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", (folder / "frames").string(), ec.message()));
  fs::create_directories(folder / "states", ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", (folder / "states").string(), ec.message()));
  return CheckRunner(manifest, folder, options, std::move(selected)).run();
}

}  // namespace particles::golden
