// Checking a golden manifest: see check.hpp. This file selects the checks and runs them, an entry's
// checks together, on a WorkerPool; golden/frame_check.hpp and golden/state_check.hpp check them.
#include "golden/check.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "input/printable_text.hpp"
#include "core/worker_pool.hpp"
#include "golden/check_context.hpp"
#include "golden/frame_check.hpp"
#include "golden/state_check.hpp"
#include "input/closest_name.hpp"
#include "output/output_error.hpp"

namespace particles::golden {

namespace fs = std::filesystem;
using scenario::GoldenCheck;
using scenario::GoldenManifest;

namespace {

// The selected checks of one entry, simulated together, and where their results go: from `slot`
// on among the frames' or the states' results.
struct CheckUnit {
  std::vector<GoldenCheck> checks;
  size_t slot = 0;
};

std::vector<CheckUnit> unitsOf(const std::vector<GoldenCheck>& selected) {
  std::vector<CheckUnit> units;
  size_t frames = 0, states = 0;
  for (const GoldenCheck& c : selected) {
    if (units.empty() || units.back().checks.front().kind != c.kind || units.back().checks.front().entry != c.entry) {
      units.push_back({{}, c.kind == GoldenCheck::Kind::frame ? frames : states});
    }
    units.back().checks.push_back(c);
    ++(c.kind == GoldenCheck::Kind::frame ? frames : states);
  }
  return units;
}

void createFolder(const fs::path& folder) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (ec) throw output::OutputError(fmt::format("cannot create {}: {}", folder.string(), ec.message()));
}

}  // namespace

std::vector<GoldenCheck> selectChecks(const GoldenManifest& manifest, const CheckOptions& options) {
  const std::vector<std::string> all = checkNames(manifest);
  for (const std::string& name : options.only) {
    if (std::find(all.begin(), all.end(), name) == all.end()) {
      const std::string closest = input::closestName(name, all);
      throw std::invalid_argument(fmt::format("no frame or state of the manifest is named {}{}",
                                              input::quotedValue(name),
                                              closest.empty() ? "" : fmt::format("; did you mean {}?", closest)));
    }
  }
  std::vector<GoldenCheck> selected;
  for (GoldenCheck& c : scenario::goldenChecks(manifest)) {
    const bool frame = c.kind == GoldenCheck::Kind::frame;
    if (!options.only.empty() && std::find(options.only.begin(), options.only.end(), c.name) == options.only.end()) {
      continue;
    }
    if (options.missingOnly) {
      // A frame that compares with another's reference has none of its own to write.
      if (frame && manifest.frames[c.entry].reference) continue;
      if (!referenceAbsent(frame ? frameReference(manifest, c.name) : stateReference(manifest, c.name))) continue;
    }
    selected.push_back(std::move(c));
  }
  if (options.shard) {
    const auto [k, n] = *options.shard;
    if (n < 1 || k < 1 || k > n)
      throw std::invalid_argument(fmt::format("--shard {}/{}: expected K/N with 1 ≤ K ≤ N", k, n));
    // Contiguous blocks keep an entry's times together: most entries are simulated in one shard.
    const size_t total = selected.size();
    const size_t begin = total * size_t(k - 1) / size_t(n), end = total * size_t(k) / size_t(n);
    selected = std::vector<GoldenCheck>(selected.begin() + long(begin), selected.begin() + long(end));
  }
  return selected;
}

CheckRun runCheck(const GoldenManifest& manifest, const fs::path& folder, const CheckOptions& options) {
  checkRenderSettings(manifest);
  const std::vector<GoldenCheck> selected = selectChecks(manifest, options);
  createFolder(folder / "frames");
  createFolder(folder / "states");
  const std::vector<CheckUnit> units = unitsOf(selected);
  CheckRun out;
  for (const GoldenCheck& c : selected) {
    if (c.kind == GoldenCheck::Kind::frame) {
      out.results.frames.emplace_back();
    } else {
      out.results.states.emplace_back();
    }
  }
  CheckContext run(manifest, folder, options, long(selected.size()));
  // Each unit writes its own results' slots only; the pool rethrows the first OutputError or
  // bad_alloc (the run's failures) once every unit has ended.
  WorkerPool pool(int(std::min(units.size(), size_t(std::max(1, options.jobs)))));
  pool.run(units.size(), [&](size_t u) {
    const CheckUnit& unit = units[u];
    if (unit.checks.front().kind == GoldenCheck::Kind::frame) {
      std::vector<FrameResult> results = checkFrames(run, unit.checks);
      std::move(results.begin(), results.end(), out.results.frames.begin() + long(unit.slot));
    } else {
      out.results.states[unit.slot] = checkState(run, unit.checks.front());
    }
  });
  out.badReference = run.badReference();
  RunFacts facts;
  facts.gl = run.gl();
  // A GPU's frames are not llvmpipe's either: golden update --from sets such a report aside too.
  facts.overrides = options.overrides.text();
  if (options.gl.gpu) facts.overrides += facts.overrides.empty() ? "--gpu" : " --gpu";
  if (options.shard) facts.shard = fmt::format("{}/{}", options.shard->first, options.shard->second);
  out.results.runs.push_back(facts);
  return out;
}

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

fs::path frameReference(const GoldenManifest& manifest, const std::string& name) {
  return manifest.references / (name + ".png");
}

fs::path stateReference(const GoldenManifest& manifest, const std::string& name) {
  return manifest.references / (name + ".csv");
}

std::vector<std::string> checkNames(const GoldenManifest& manifest) {
  std::vector<std::string> names;
  for (const GoldenCheck& c : scenario::goldenChecks(manifest)) names.push_back(c.name);
  return names;
}

}  // namespace particles::golden
