#include "commands.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <optional>

#include "damped_spring_force.hpp"
#include "cli_support.hpp"
#include "output_file.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario.hpp"

namespace particles::cli {

namespace {

using scenario::Scenario;

// The points the trace follows: every particle and body, or those named by --trace-only.
std::optional<std::vector<int>> tracePoints(const System& system, const std::vector<std::string>& only) {
  const Model& model = system.model();
  std::vector<std::string> names;
  for (int p = 0; p < model.layout.numPoints(); ++p) names.push_back(scenario::pointName(model, p));
  std::vector<int> points;
  if (only.empty()) {
    for (int p = 0; p < model.layout.numPoints(); ++p) points.push_back(p);
    return points;
  }
  for (const std::string& name : only) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end()) {
      fmt::print(stderr,
                 "error: --trace-only: nothing in the scenario is named '{}' (names are spelled as in the "
                 "trace: bob, cloth[3][4], link0, #7)\n",
                 name);
      return std::nullopt;
    }
    points.push_back(int(it - names.begin()));
  }
  return points;
}

}  // namespace

int checkCommand(const CommonOptions& common) {
  const auto s = loadScenario(common);
  if (!s) return kBadInput;
  if (!common.quiet) {
    const auto& sim = s->simulation;
    fmt::print("{}: ok: '{}' with {}; {}, dt {} s, duration {} s ({})\n", common.scenario, s->name, contents(*s),
               integratorName(sim.integrator), sim.dt, sim.duration, plural(size_t(sim.steps()), "step", "steps"));
  }
  return kOk;
}

int runCommand(const CommonOptions& common, const RunOptions& options) {
  auto s = loadScenario(common);
  if (!s) return kBadInput;
  if (!options.stats.empty() && options.stats == options.trace) {
    fmt::print(stderr, "error: --stats and --trace name the same file '{}'\n", options.stats);
    return kBadInput;
  }
  const auto points = tracePoints(s->system, options.traceOnly);
  if (!points) return kBadInput;

  try {
    std::optional<OutputFile> stats, trace;
    if (!options.stats.empty()) {
      stats.emplace(options.stats);
      stats->write("t,kinetic,potential,total,constraint_error,penetration\n");
    }
    if (!options.trace.empty()) {
      trace.emplace(options.trace);
      trace->write("t,name,x,y,vx,vy,angle,omega\n");
    }
    std::vector<std::string> names;
    for (int p : *points) names.push_back(scenario::pointName(s->system.model(), p));

    fmt::memory_buffer buffer;
    scenario::RunObserver observer;
    observer.onTick = [&](const System& system) {
      if (stats) {
        const scenario::Sample x = scenario::sampleOf(system);
        buffer.clear();
        fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{}\n", x.t, x.kinetic, x.potential, x.total,
                       x.constraintError, x.penetration);
        stats->write({buffer.data(), buffer.size()});
      }
      if (trace) {
        const StateView v = system.view();
        const int numParticles = system.layout().numParticles;
        buffer.clear();
        for (size_t k = 0; k < points->size(); ++k) {
          const int p = (*points)[k];
          const Vec2 x = v.pos(p), u = v.vel(p);
          const double angle = p < numParticles ? 0.0 : v.angle(p - numParticles);
          const double omega = p < numParticles ? 0.0 : v.omega(p - numParticles);
          fmt::format_to(std::back_inserter(buffer), "{},{},{},{},{},{},{},{}\n", system.time(), names[k], x.x(), x.y(),
                         u.x(), u.y(), angle, omega);
        }
        trace->write({buffer.data(), buffer.size()});
      }
    };
    Progress progress(!common.quiet, "steps");
    const System& system = s->system;
    observer.onStep = [&](long step, long steps) { progress.update(step, steps, fmt::format("t = {:.3f} s", system.time())); };

    scenario::RunSummary summary;
    try {
      summary = scenario::runScenario(*s, observer);
    } catch (const SimulationError& e) {
      progress.finish();
      fmt::print(stderr, "{}: error: {}\n", common.scenario, e.what());
      return kSimulationFailed;  // the outputs are removed as they go out of scope uncommitted
    }
    progress.finish();
    if (stats) stats->commit();
    if (trace) trace->commit();

    if (!common.quiet) {
      const auto& sim = s->simulation;
      const EnergyReport& e = summary.finalEnergy;
      const double ratio = summary.wallSeconds > 0.0 ? summary.simulatedTime / summary.wallSeconds : 0.0;
      fmt::print("scenario          {} ({})\n", s->name, common.scenario);
      fmt::print("particles         {}\n", system.layout().numParticles);
      fmt::print("rigid bodies      {}\n", system.layout().numBodies);
      fmt::print("springs           {}\n", scenario::springCount(system));
      fmt::print("constraints       {}\n", system.constraints().size());
      fmt::print("colliders         {}\n", system.colliders().size());
      fmt::print("integrator        {}\n", integratorName(sim.integrator));
      fmt::print("dt                {} s\n", sim.dt);
      fmt::print("steps             {}\n", summary.steps);
      fmt::print("simulated time    {:.6g} s\n", summary.simulatedTime);
      fmt::print("wall time         {:.3f} s\n", summary.wallSeconds);
      fmt::print("sim/wall ratio    {:.3g}\n", ratio);
      fmt::print("final energy      {:.6g} J (kinetic {:.6g} J, potential {:.6g} J; initial total {:.6g} J)\n",
                 e.total(), e.kinetic, e.potential, summary.initialEnergy.total());
      fmt::print("constraint error  {:.3g} m (worst over the run)\n", summary.worstConstraintError);
      fmt::print("penetration       {:.3g} m (worst over the run)\n", summary.worstPenetration);
      if (stats) fmt::print("stats             {}\n", options.stats);
      if (trace) fmt::print("trace             {}\n", options.trace);
    }
    return kOk;
  } catch (const OutputError& e) {
    fmt::print(stderr, "error: {}\n", e.what());
    return kOutputFailed;
  }
}

}  // namespace particles::cli
