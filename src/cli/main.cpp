// The `particles` program (DESIGN §12): command-line parsing with CLI11; the work is in commands.cpp.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "commands.hpp"

namespace {

using particles::cli::CommonOptions;

void addCommonOptions(CLI::App& command, CommonOptions& o) {
  command.add_option("scenario", o.scenario, "Scenario file (YAML, see docs/scenarios.md)")->required();
  command.add_option("--integrator", o.integrator, "Override simulation.integrator: euler | midpoint | rk4");
  command.add_option("--dt", o.dt, "Override simulation.dt, the time step in seconds");
  command.add_option("--duration", o.duration, "Override simulation.duration, in simulated seconds");
  command.add_option("--set", o.sets, "Override any key before validation: --set path.to.key=value (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  command.add_flag("-q,--quiet", o.quiet, "No progress and no summary; errors are still printed");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"particles: 2D particle systems and rigid bodies after Witkin & Baraff", "particles"};
  app.set_version_flag("--version", "particles " PARTICLES_VERSION);
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 simulation failure (explosion), 2 bad input or usage, 3 output failure.\n"
      "Run 'particles COMMAND --help' for the options of a command.\n");

  CommonOptions common;
  particles::cli::RunOptions run;

  CLI::App* check = app.add_subcommand("check", "Validate a scenario file without simulating (exit 0 or 2)");
  addCommonOptions(*check, common);
  check->footer(
      "Examples:\n"
      "  particles check scenarios/cloth.yaml\n"
      "  particles check my.yaml --set simulation.dt=0.005 --set forces[1].kd=0.1\n");

  CLI::App* runCmd = app.add_subcommand("run", "Simulate a scenario headless for its duration and print a summary");
  addCommonOptions(*runCmd, common);
  runCmd->add_option("--stats", run.stats,
                     "Write t,kinetic,potential,total,constraint_error,penetration per 1/fps tick to this CSV");
  auto* trace = runCmd->add_option(
      "--trace", run.trace, "Write t,name,x,y,vx,vy,angle,omega of every particle and body per tick to this CSV");
  runCmd->add_option("--trace-only", run.traceOnly, "Trace only these objects (comma-separated names)")
      ->delimiter(',')
      ->needs(trace);
  runCmd->footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml\n"
      "  particles run scenarios/soft_body.yaml --stats man.csv --integrator midpoint --dt 0.05\n"
      "  particles run scenarios/rod_pendulum.yaml --trace pendulum.csv --trace-only bob\n"
      "  particles run scenarios/springs.yaml --duration 2 --quiet --stats springs.csv\n");

  particles::cli::StabilityOptionsCli stability;
  CLI::App* stabilityCmd = app.add_subcommand(
      "stability", "Find the largest stable time step of each integrator on a scenario (simulation only)");
  addCommonOptions(*stabilityCmd, common);
  stabilityCmd->add_option("--integrators", stability.integrators, "Integrators to study, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  stabilityCmd->add_option("--csv", stability.csv,
                           "Write integrator,evals_per_step,max_stable_dt,max_smooth_dt,evals_per_sim_second,"
                           "speed_vs_euler to this CSV");
  stabilityCmd->add_option("--plot", stability.plot, "Write the table as a bar chart (log axis): .svg or .png");
  stabilityCmd->add_option("--energy-tolerance", stability.energyTolerance,
                           "Unstable when energy exceeds E(0) + mouse work by this fraction of the energy scale")
      ->capture_default_str();
  stabilityCmd->add_option("--stretch-factor", stability.stretchFactor,
                           "Unstable when a spring stretches beyond this multiple of the largest stretch of a "
                           "reference run (rk4 at a quarter of the scenario's dt)")
      ->capture_default_str();
  stabilityCmd->add_option("--shake-threshold", stability.shakeThreshold,
                           "Shaking when the step-alternating share of velocity exceeds this (sin²(ωh/2))")
      ->capture_default_str();
  stabilityCmd->add_option("--min-dt", stability.minDt, "Smallest dt tried, s (default: the scenario's dt / 1000)");
  stabilityCmd->add_option("--max-dt", stability.maxDt, "Largest dt tried, s")->capture_default_str();
  stabilityCmd->add_option("--threads", stability.threads, "Integrators studied at once (0: one per core)")
      ->capture_default_str();
  stabilityCmd->footer(
      "Criteria and the report's results: docs/stability.md.\n"
      "Examples:\n"
      "  particles stability scenarios/cloth.yaml\n"
      "  particles stability scenarios/cloth.yaml --csv cloth_dt.csv --plot cloth_dt.svg\n"
      "  particles stability scenarios/soft_body.yaml --integrators midpoint,rk4 --duration 20\n");

  particles::cli::PlotOptions plotOptions;
  CLI::App* plotCmd = app.add_subcommand("plot", "Draw the figure of a --stats CSV: energy and constraint error over time");
  plotCmd->add_option("stats", plotOptions.input, "A CSV written by run/render --stats")->required();
  plotCmd->add_option("-o,--output", plotOptions.output, "The figure: .svg (vector) or .png")->required();
  plotCmd->add_option("--title", plotOptions.title, "Title above the chart");
  plotCmd->add_option("--width", plotOptions.width, "Width in px (default 1200)")->check(CLI::Range(200, 10000));
  plotCmd->add_option("--height", plotOptions.height, "Height in px (default 800)")->check(CLI::Range(150, 10000));
  plotCmd->add_flag("-q,--quiet", plotOptions.quiet, "Print nothing on success");
  plotCmd->footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml --stats cloth.csv && particles plot cloth.csv -o energy.svg\n"
      "  particles plot cloth.csv -o energy.png --title 'Cloth, RK4, dt = 0.01 s'\n");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version or the error
    return code == 0 ? particles::cli::kOk : particles::cli::kBadInput;
  }
  try {
    if (check->parsed()) return particles::cli::checkCommand(common);
    if (stabilityCmd->parsed()) return particles::cli::stabilityCommand(common, stability);
    if (plotCmd->parsed()) return particles::cli::plotCommand(plotOptions);
    return particles::cli::runCommand(common, run);
  } catch (const std::exception& e) {
    // Every expected failure is handled in the commands; this is a bug, reported rather than aborted.
    std::fprintf(stderr, "particles: internal error: %s\n", e.what());
    return particles::cli::kSimulationFailed;
  }
}
