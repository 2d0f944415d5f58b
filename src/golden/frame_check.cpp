// The frame checks of one entry: see frame_check.hpp.
#include "golden/frame_check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <new>
#include <span>

#include "golden/check_settings.hpp"
#include "golden/reproduce_commands.hpp"
#include "output/output_error.hpp"
#include "render/image_compare.hpp"
#include "render/png_io.hpp"
#include "render/renderer.hpp"
#include "render/styled_run.hpp"

namespace particles::golden {

namespace fs = std::filesystem;
using scenario::GoldenEntry;

namespace {

class FrameComparison {
 public:
  FrameComparison(CheckContext& run, const GoldenEntry& entry, const render::CompareTolerance& tolerance,
                  const render::PngOptions& png)
      : run_(run), o_(run.options()), entry_(entry), tolerance_(tolerance), png_(png) {}

  // Compares `actual` with the reference of `r` and keeps the files the report shows.
  void compare(FrameResult& r, const render::Image& actual) {
    const fs::path reference = r.reference;
    const std::string actualFile = "frames/" + r.name + ".actual.png";
    const std::string expectedFile = "frames/" + r.name + ".expected.png";
    const std::string diffFile = "frames/" + r.name + ".diff.png";
    auto keepActual = [&](bool always) {
      if (always || !o_.keepAll) keep(actualFile, actual, png_);
      r.files.actual = actualFile;
    };
    if (o_.keepAll) keepActual(true);
    if (referenceAbsent(reference)) {
      r.outcome = Outcome::missing;
      r.message = entry_.reference ? fmt::format(
                                         "no reference {} yet: this check compares with frame {}'s reference, which "
                                         "`golden update` writes for the manifest that has frame {}",
                                         shownPath(reference), entry_.reference->value, entry_.reference->value)
                                   : noReferenceYet(o_, shownPath(reference));
      keepActual(false);
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
      run_.unusableReference(r, ex);
      return;
    }
    r.reproduce.insert(r.reproduce.begin() + 1, compareCommand(o_, r.reference, r.name, tolerance_));
    auto keepExpected = [&] {
      writeText(run_.folder() / expectedFile, bytes);
      r.files.expected = expectedFile;
    };
    if (!mismatch.empty()) {
      r.outcome = Outcome::failed;
      r.message = fmt::format("the frame and its reference differ in size: {}", mismatch);
      keepActual(false);
      keepExpected();
      return;
    }
    const render::ImageComparison c = render::compareImages(expected, actual, tolerance_);
    r.numbers = frameNumbersOf(c, tolerance_);
    const bool differs = !c.passed;
    r.outcome = differs == r.expectDiffer ? Outcome::passed : Outcome::failed;
    if (r.outcome == Outcome::failed) {
      r.message =
          r.expectDiffer
              ? fmt::format(
                    "a control that must differ matches its reference ({} pixels of {} "
                    "differ; the bound is {:.4g} %): the check cannot see this change",
                    c.differing, c.pixels, 100.0 * tolerance_.maxShare)
              : fmt::format("{:.4f} % of the pixels differ by more than {} ({} of {}; bound {:.4g} %)", 100.0 * c.share,
                            tolerance_.threshold, c.differing, c.pixels, 100.0 * tolerance_.maxShare);
    }
    if (r.outcome == Outcome::failed || r.expectDiffer) {
      keepActual(false);
      keep(diffFile, render::diffImage(expected, actual, tolerance_.threshold), {});
      r.files.diff = diffFile;
      if (r.outcome == Outcome::failed) keepExpected();
    }
  }

 private:
  void keep(const fs::path& relative, const render::Image& image, const render::PngOptions& png) {
    render::writePng(run_.folder() / relative, image, png);
  }

  CheckContext& run_;
  const CheckOptions& o_;
  const GoldenEntry& entry_;
  const render::CompareTolerance tolerance_;
  const render::PngOptions png_;
};

// The steps from the start to the entry's last time (the trails' bound, style/trail_history.hpp).
long stepsToLastTime(const GoldenEntry& e, const scenario::Scenario& s) {
  double last = 0.0;
  for (const scenario::GoldenTime& t : e.times) last = std::max(last, t.seconds);
  return long(std::ceil(last / s.simulation.dt)) + 1;
}

}  // namespace

std::vector<FrameResult> checkFrames(CheckContext& run, const std::vector<scenario::GoldenCheck>& checks) {
  const scenario::GoldenManifest& m = run.manifest();
  const CheckOptions& o = run.options();
  const GoldenEntry& e = m.frames[checks.front().entry];
  auto start = std::chrono::steady_clock::now();
  std::vector<FrameResult> results(checks.size());
  for (size_t i = 0; i < checks.size(); ++i) {
    FrameResult& r = results[i];
    r.name = checks[i].name;
    r.scenario = e.scenarioGiven;
    r.time = e.times[checks[i].time].text;
    r.expectDiffer = e.expectDiffer;
    r.reference = shownPath(frameReference(m, e.reference ? e.reference->value : r.name));
    r.reproduce.push_back(checkCommand(o, r.name));
  }
  size_t next = 0;  // the first check without an outcome
  auto finish = [&](FrameResult& r) {
    r.seconds = secondsSince(start);
    start = std::chrono::steady_clock::now();
    ++next;
    run.done(r.name);
  };
  try {
    EntrySimulation simulation(m, e, o.maxInputMiB);
    const scenario::Scenario& s = simulation.scenario();
    const render::RenderOptions look = frameLookOf(m, e, o.overrides, {s.render.width, s.render.height});
    render::validate(look);
    const render::Camera camera{s.render.viewCenter, s.render.viewHeight};
    // Each frame is drawn as `particles render --at` draws it (the command reproduce gives): its
    // style's automatic ranges and fitted camera are its own frame's (StyledRun::fitTo), its trails
    // and followed camera the run's up to it.
    render::StyledRun styled(s.style, s.render.view, camera, look, s.simulation.dt, stepsToLastTime(e, s));
    render::Renderer renderer(styled.look(), o.gl);
    run.noteGl(renderer.gl());
    styled.start(s.system);
    render::StyledFrameBuffers buffers;
    render::PngOptions png;
    png.alpha = look.transparentBackground;
    FrameComparison comparison(run, e, compareToleranceOf(m, e, o.overrides), png);
    for (size_t i = 0; i < checks.size(); ++i) {
      const scenario::GoldenTime& t = e.times[checks[i].time];
      FrameResult& r = results[next];
      r.reproduce.insert(r.reproduce.begin(), renderCommand(o, e, r.name, t.text, look));
      if (const std::string why = simulation.unreachable(t); !why.empty()) {
        r.outcome = Outcome::error;
        r.message = why;
        finish(r);
        continue;
      }
      simulation.advanceTo(t, &styled);
      comparison.compare(r, render::drawStyledFrame(simulation.system(), styled, renderer, buffers, true));
      finish(r);
    }
  } catch (const output::OutputError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& ex) {  // the scenario, the simulation, the renderer
    while (next < results.size()) {
      results[next].outcome = Outcome::error;
      results[next].message = ex.what();
      finish(results[next]);
    }
  }
  return results;
}

}  // namespace particles::golden
