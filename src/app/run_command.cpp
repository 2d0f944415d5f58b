// `particles run`: see run_command.hpp.
#include "app/run_command.hpp"

#include <fmt/format.h>

#include "app/cli_support.hpp"
#include "app/csv_recorder.hpp"
#include "app/job_record.hpp"
#include "scenario/runner.hpp"
#include "scenario/scenario.hpp"

namespace particles::app {

namespace {

void addRunOptions(CLI::App& command, RunOptions& o) {
  addCommonOptions(command, o.common);
  command.add_option("--stats", o.stats,
                     "Write t,kinetic,potential,total,constraint_error,penetration per 1/fps tick to this CSV");
  auto* trace = command.add_option(
      "--trace", o.trace, "Write t,name,x,y,vx,vy,angle,omega of every particle and body per tick to this CSV");
  command.add_option("--trace-only", o.traceOnly, "Trace only these objects (comma-separated names)")
      ->delimiter(',')
      ->needs(trace);
  command.footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml\n"
      "  particles run scenarios/soft_body.yaml --stats man.csv --integrator midpoint --dt 0.05\n"
      "  particles run scenarios/rod_pendulum.yaml --trace pendulum.csv --trace-only bob\n"
      "  particles run scenarios/springs.yaml --duration 2 --quiet --stats springs.csv\n");
  addJobOptions(command, o.job);
}

int runCommand(const RunOptions& options) {
  const CommonOptions& common = options.common;
  scenario::Scenario s = loadScenario(common);
  // A SimulationError leaves the CSVs uncommitted: they are removed as they go out of scope.
  auto recorder = CsvRecorder::open(s.system, s.render.fps, options.stats, options.trace, options.traceOnly);
  scenario::RunObserver observer;
  observer.onTick = [&](const System& system) { recorder->record(system); };
  Progress progress(!common.quiet, "steps");
  const System& system = s.system;
  observer.onStep = [&](long step, long steps) {
    progress.update(step, steps, fmt::format("t = {:.3f} s", system.time()));
  };

  const scenario::RunSummary summary = scenario::runScenario(s, observer);
  progress.finish();
  recorder->commit();
  reportHeadline("final_energy", summary.finalEnergy.total());
  reportHeadline("initial_energy", summary.initialEnergy.total());
  reportHeadline("worst_constraint_error", summary.worstConstraintError);
  reportHeadline("worst_penetration", summary.worstPenetration);
  reportHeadline("steps", double(summary.steps));
  reportHeadline("wall_seconds", summary.wallSeconds);

  if (!common.quiet) {
    const auto& sim = s.simulation;
    const EnergyReport& e = summary.finalEnergy;
    const double ratio = summary.wallSeconds > 0.0 ? summary.simulatedTime / summary.wallSeconds : 0.0;
    fmt::print("scenario          {} ({})\n", s.name, common.scenario);
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
    fmt::print("final energy      {:.6g} J (kinetic {:.6g} J, potential {:.6g} J; initial total {:.6g} J)\n", e.total(),
               e.kinetic, e.potential, summary.initialEnergy.total());
    fmt::print("constraint error  {:.3g} m (worst over the run)\n", summary.worstConstraintError);
    fmt::print("penetration       {:.3g} m (worst over the run)\n", summary.worstPenetration);
    if (recorder->writesStats()) fmt::print("stats             {}\n", options.stats);
    if (recorder->writesTrace()) fmt::print("trace             {}\n", options.trace);
  }
  return kOk;
}

CommandFiles runFiles(const RunOptions& o) {
  return {{{"--stats", o.stats}, {"--trace", o.trace}}, {{"the scenario", o.common.scenario}}};
}

}  // namespace

const CommandDescriptor<RunOptions> kRunCommand = {
    .name = "run",
    .summary = "Simulate a scenario headless for its duration and print a summary",
    .addOptions = addRunOptions,
    .run = runCommand,
    .files = runFiles,
    .common = &RunOptions::common,
    .job = &RunOptions::job,
};

}  // namespace particles::app
