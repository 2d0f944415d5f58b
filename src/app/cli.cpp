// The command line: see cli.hpp. Each command's work is in its own file (commands.cpp: check and
// run; render_, stability_, plot_, compare_, concat_, sweep_, gather_ and schema_command.cpp);
// errors become exit codes and messages in exit_codes.cpp only.
#include "app/cli.hpp"

#include <fmt/format.h>

#include "app/cli_support.hpp"
#include "app/exit_codes.hpp"
#include "app/gl_options.hpp"
#include "app/job_record.hpp"
#include "render/frame_writer.hpp"
#include "render/gl_backend.hpp"
#include "render/output_formats.hpp"
#include "render/renderer.hpp"

namespace particles::app {

namespace {

void addCommonOptions(CLI::App& command, CommonOptions& o) {
  command.add_option("scenario", o.scenario, "Scenario file (YAML, see docs/scenarios.md)")->required();
  command.add_option("--integrator", o.integrator,
                     fmt::format("Override simulation.integrator: {}", fmt::join(integratorNames(), " | ")));
  command.add_option("--dt", o.dt, "Override simulation.dt, the time step in seconds");
  command.add_option("--duration", o.duration, "Override simulation.duration, in simulated seconds");
  command.add_option("--set", o.sets, "Override any key before validation: --set path.to.key=value (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  command.add_flag("-q,--quiet", o.quiet, "No progress and no summary; errors are still printed");
  addMaxInputOption(command, o.maxInputMiB, "a scenario file");
  command
      .add_option("--limit", o.limits,
                  "Raise (or lower) a scene limit, counted before anything is built: particles, springs, "
                  "constraints, endpoints or entries (repeatable; defaults in docs/scenarios.md, Limits)")
      ->type_name("NAME=N")
      ->allow_extra_args(false);
}

}  // namespace

Cli::Cli() {
  // The version, and on a second line the GL backend and renderer `render` would use.
  app.set_version_flag("--version", [] { return "particles " + programVersion() + "\n" + glVersionLine(); });
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 simulation failure (explosion; for compare: the frames differ),\n"
      "2 bad input or usage, 3 output failure.\n"
      "Run 'particles COMMAND --help' for the options of a command.\n");

  checkCmd = app.add_subcommand("check", "Validate a scenario file without simulating (exit 0 or 2)");
  addCommonOptions(*checkCmd, common);
  checkCmd->footer(
      "Examples:\n"
      "  particles check scenarios/cloth.yaml\n"
      "  particles check my.yaml --set simulation.dt=0.005 --set forces[1].kd=0.1\n");

  runCmd = app.add_subcommand("run", "Simulate a scenario headless for its duration and print a summary");
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

  renderCmd = app.add_subcommand(
      "render", "Simulate and draw the scenario off-screen to an MP4, WebM or GIF video, PNG frames or one PNG");
  addCommonOptions(*renderCmd, common);
  renderCmd->add_option("-o,--output", render.output, render::outputHelp())->required();
  renderCmd->add_option("--at", render.at, render::atHelp());
  renderCmd->add_option("--frames", render.frames, render::framesHelp());
  renderCmd->add_option("--size", render.size, "Frame size WxH in px (default: the scenario's render.size)");
  renderCmd->add_option("--fps", render.fps, render::fpsHelp());
  renderCmd->add_option("--msaa", render.msaa, "Anti-aliasing samples per pixel: 1 (off), 2, 4, 8 or 16")
      ->check(CLI::IsMember(render::kSampleCounts))
      ->capture_default_str();
  renderCmd
      ->add_option("--raster", render.raster,
                   "How shapes become pixels: triangles (one GL primitive each), tiles (sorted into screen tiles "
                   "on the CPU, one pass; fast for large scenes) or auto (tiles from 5000 shapes)")
      ->check(CLI::IsMember({"auto", "triangles", "tiles"}))
      ->capture_default_str();
  renderCmd->add_option("--theme", render.theme, "dark (screens) or light (printed reports)")->capture_default_str();
  renderCmd->add_option("--background", render.background, render::backgroundHelp())->capture_default_str();
  renderCmd->add_option("--particle-radius", render.particleRadius,
                        "Particle disc radius: 4px (pixels) or 0.02m (world)");
  renderCmd->add_option("--crf", render.crf, render::crfHelp());
  renderCmd
      ->add_option("--keyint", render.keyint,
                   "Longest time between keyframes, s (MP4, WebM): players seek to a keyframe, so shorter seeks "
                   "faster")
      ->check(CLI::Range(1e-3, render::kMaxKeyintSeconds))
      ->capture_default_str();
  renderCmd->add_option("--preset", render.preset, "x264 preset (MP4): ultrafast … veryslow")->capture_default_str();
  renderCmd->add_option("--png-level", render.pngLevel, "PNG compression level 0 … 9")->capture_default_str();
  renderCmd->add_flag("--verbose", render.verbose, "Name the GL backend and renderer; show libav/x264's own log");
  renderCmd
      ->add_option("--gl", render.gl,
                   fmt::format("GL backend: auto (EGL, else OSMesa), egl or osmesa (default: ${}, else auto)",
                               kGlEnvironmentVariable))
      ->check(CLI::IsMember(render::glBackendNames()));
  renderCmd->add_flag("--gpu", render.gpu,
                      "Draw on a GPU through EGL instead of llvmpipe on the CPU (frames may differ from the goldens)");
  renderCmd->add_flag("--hud", render.hud,
                      "Draw time, integrator, dt and energy in the top-left corner of every frame");
  renderCmd->add_option("--stats", render.stats,
                        "Write t,kinetic,potential,total,constraint_error,penetration per frame");
  auto* renderTrace = renderCmd->add_option("--trace", render.trace, "Write t,name,x,y,vx,vy,angle,omega per frame");
  renderCmd->add_option("--trace-only", render.traceOnly, "Trace only these objects (comma-separated names)")
      ->delimiter(',')
      ->needs(renderTrace);
  renderCmd->footer(
      "Frame i shows t = i / fps; a video has round(duration · fps) frames. Odd sizes are refused for MP4\n"
      "and WebM (yuv420p needs even sizes); GIF and PNG take any size. A GIF has one palette made for the\n"
      "whole video, at most 50 fps (30 unless --fps says), delays rounded to whole centiseconds.\n"
      "--background transparent keeps alpha in PNG and WebM (VP9 with an alpha channel); MP4 and GIF\n"
      "refuse it. --frames (split renders) is for MP4 and PNG sequences. Outputs appear only when complete.\n"
      "Frames are drawn by Mesa's llvmpipe on the CPU, the same bytes through EGL or OSMesa;\n"
      "'particles --version' names the backend and renderer.\n"
      "Examples:\n"
      "  particles render scenarios/cloth.yaml -o cloth.mp4\n"
      "  particles render scenarios/soft_body.yaml -o frames/ --size 640x360 --fps 30\n"
      "  particles render scenarios/cloth.yaml -o fig.png --at 2.5 --theme light --size 1600x1200\n"
      "  particles render scenarios/soft_body.yaml -o man.mp4 --hud   # time, integrator, dt, energy on every frame\n"
      "  particles render scenarios/rigid_chain.yaml -o chain.mp4 --crf 23 --preset veryfast --quiet\n"
      "  particles render scenarios/cloth.yaml -o cloth.gif --size 480x270   # 30 fps, a palette for the video\n"
      "  particles render scenarios/cloth.yaml -o cloth.webm --background transparent   # VP9 with alpha\n"
      "  PARTICLES_GL=osmesa particles render scenarios/cloth.yaml -o cloth.mp4   # where EGL will not start\n");

  stabilityCmd = app.add_subcommand(
      "stability", "Find the largest stable time step of each integrator on a scenario (simulation only)");
  addCommonOptions(*stabilityCmd, common);
  stabilityCmd->add_option("--integrators", stability.integrators, "Integrators to study, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  stabilityCmd->add_option("--csv", stability.csv,
                           "Write integrator,evals_per_step,max_stable_dt,max_smooth_dt,cost_dt,evals_per_sim_second,"
                           "speed_vs_euler,wall_seconds_per_sim_second to this CSV");
  stabilityCmd->add_option("--plot", stability.plot,
                           "Write the limits as a dot plot (log axis, criteria in the caption): .svg, .png or .pdf");
  stabilityCmd
      ->add_option("--reference", stability.references,
                   "Values to show beside the limits on the plot, per integrator: NAME=DT (a point) or NAME=LO:HI "
                   "(the limit lies between), e.g. euler=0.003:0.005,rk4=0.3")
      ->delimiter(',')
      ->type_name("NAME=DT");
  stabilityCmd->add_option("--reference-name", stability.referenceName, "What the references are, in the legend")
      ->capture_default_str();
  stabilityCmd
      ->add_option("--energy-tolerance", stability.energyTolerance,
                   "Unstable when energy exceeds E(0) + mouse work by this fraction of the energy scale")
      ->capture_default_str();
  stabilityCmd
      ->add_option("--stretch-factor", stability.stretchFactor,
                   "Unstable when a spring stretches beyond this multiple of the largest stretch of a "
                   "reference run (rk4 at a quarter of the scenario's dt, halved up to six times until stable)")
      ->capture_default_str();
  stabilityCmd
      ->add_option("--shake-threshold", stability.shakeThreshold,
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
      "  particles stability scenarios/soft_body.yaml --integrators midpoint,rk4 --duration 20\n"
      "  particles stability scenarios/cloth_report.yaml --integrators euler,midpoint,rk4 --plot dt.pdf \\\n"
      "      --reference euler=0.003:0.005,midpoint=0.03:0.05,rk4=0.3:0.4 --reference-name report\n");

  compareCmd = addCompareCommand(app, compare);

  concatCmd = addConcatCommand(app, concat);
  addJobOptions(*concatCmd, job);

  plotCmd = app.add_subcommand("plot", "Draw the figure of a --stats CSV: energy and constraint error over time");
  plotCmd->add_option("stats", plot.input, "A CSV written by run/render --stats")->required();
  plotCmd->add_option("-o,--output", plot.output, "The figure: .svg (vector), .pdf (vector, for LaTeX) or .png")
      ->required();
  plotCmd->add_option("--title", plot.title, "Title above the chart (default: scenario, integrator and dt)");
  auto* plotScenario = plotCmd->add_option(
      "--scenario", plot.scenario,
      "The scenario that was run: names it, its integrator and dt in the title and shades the mouse's intervals");
  plotCmd->add_option("--integrator", plot.integrator, "The run's --integrator, if it had one")->needs(plotScenario);
  plotCmd->add_option("--dt", plot.dt, "The run's --dt, if it had one")->needs(plotScenario);
  plotCmd->add_option("--set", plot.sets, "The run's --set overrides, if it had any (repeatable)")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false)
      ->needs(plotScenario);
  plotCmd->add_option("--width", plot.width, "Width in px (default 1200)")->check(CLI::Range(200, 10000));
  plotCmd->add_option("--height", plot.height, "Height in px (default 800)")->check(CLI::Range(150, 10000));
  plotCmd->add_flag("-q,--quiet", plot.quiet, "Print nothing on success");
  addMaxInputOption(*plotCmd, plot.maxInputMiB, "a CSV file");
  plotCmd->footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml --stats cloth.csv && particles plot cloth.csv -o energy.svg\n"
      "  particles plot cloth.csv -o energy.png --title 'Cloth, RK4, dt = 0.01 s'\n"
      "  particles run scenarios/soft_body.yaml --stats man.csv --dt 0.1\n"
      "  particles plot man.csv --scenario scenarios/soft_body.yaml --dt 0.1 -o man.pdf   # mouse intervals shaded\n");

  schemaCmd =
      app.add_subcommand("schema", "Print the scenario format as JSON Schema (draft 7), for editors and validators");
  schemaCmd->add_flag("--markdown", schema.markdown, "Print each kind's key table as docs/scenarios.md has it");
  schemaCmd->footer(
      "Examples:\n"
      "  particles schema > scenario.schema.json\n"
      "  # then, at the top of a scenario: # yaml-language-server: $schema=scenario.schema.json\n"
      "  particles schema --markdown\n");

  addJobOptions(*runCmd, job);
  addJobOptions(*renderCmd, job);
  addJobOptions(*stabilityCmd, job);
  sweepCmd = addSweepCommand(app, sweep);
  gatherCmd = addGatherCommand(app, gather);
  runJobCmd = addRunJobCommand(app, runJob);
}

CommandFiles Cli::commandFiles() const {
  const output::NamedFile scenario{"the scenario", common.scenario};
  if (runCmd->parsed()) return {{{"--stats", run.stats}, {"--trace", run.trace}}, {scenario}};
  if (renderCmd->parsed()) {
    return {{{"-o", render.output}, {"--stats", render.stats}, {"--trace", render.trace}}, {scenario}};
  }
  if (stabilityCmd->parsed()) return {{{"--csv", stability.csv}, {"--plot", stability.plot}}, {scenario}};
  if (plotCmd->parsed()) return {{{"-o", plot.output}}, {{"the CSV", plot.input}, {"--scenario", plot.scenario}}};
  if (compareCmd->parsed()) {
    return {{{"--diff", compare.diff}},
            {{"the expected frame", compare.expected}, {"the actual frame", compare.actual}}};
  }
  if (concatCmd->parsed()) {
    CommandFiles files{{{"-o", concat.output}}, {}};
    for (const std::string& segment : concat.segments) files.inputs.push_back({"the segment", segment});
    return files;
  }
  return {};
}

int Cli::dispatch(const std::vector<std::string>& args) {
  const ErrorContext context{.scenario = common.scenario};
  auto command = [&] {
    if (checkCmd->parsed()) return checkCommand(common);
    if (schemaCmd->parsed()) return schemaCommand(schema);
    if (stabilityCmd->parsed()) return stabilityCommand(common, stability);
    if (plotCmd->parsed()) return plotCommand(plot);
    if (compareCmd->parsed()) return compareCommand(compare);
    if (concatCmd->parsed()) return concatCommand(concat);
    if (renderCmd->parsed()) return renderCommand(common, render);
    if (sweepCmd->parsed()) return sweepCommand(sweep);
    if (gatherCmd->parsed()) return gatherCommand(gather);
    if (runJobCmd->parsed()) return runJobCommand(runJob);
    return runCommand(common, run);
  };
  CommandFiles files = commandFiles();
  std::vector<std::string> outputs;  // what a job record lists, before --record joins them
  for (const output::NamedFile& f : files.outputs) {
    if (!f.path.empty()) outputs.push_back(f.path.string());
  }
  if (!job.record.empty()) files.outputs.push_back({"--record", job.record});
  // Before anything runs, and before a record is read or written: a --record that names another of
  // the command's files, a folder or a missing folder is refused without writing it.
  const int refused = runReportingErrors(context, [&] {
    if (!job.record.empty()) requireRecordPath(job.record);
    output::requireDistinctFiles(files.outputs, files.inputs);
    return kOk;
  });
  if (refused != kOk) return refused;
  if (job.record.empty()) return runReportingErrors(context, command);
  // A sweep's job: skipped when its record says it is done, recorded whatever its outcome.
  if (!concatCmd->parsed()) job.maxInputMiB = common.maxInputMiB;
  return runRecordedJob(job, args, outputs, context, command);
}

}  // namespace particles::app
