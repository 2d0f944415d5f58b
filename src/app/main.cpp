// The `particles` program (docs/physics.md §12): the command line, parsed with CLI11. Each command's
// work is in its own file (commands.cpp: check and run; render_, stability_, plot_, compare_ and
// schema_command.cpp); errors become exit codes and messages in exit_codes.cpp only.
#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <malloc.h>

#include "app/commands.hpp"
#include "app/compare_command.hpp"
#include "app/concat_command.hpp"
#include "app/exit_codes.hpp"
#include "app/gl_options.hpp"
#include "render/frame_writer.hpp"
#include "render/gl_backend.hpp"
#include "render/renderer.hpp"

namespace {

using particles::app::CommonOptions;
using particles::app::integratorNames;

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
  command.add_option("--max-input", o.maxInputMiB, "Refuse a scenario file larger than this, MiB")
      ->check(CLI::Range(std::uintmax_t(1), std::uintmax_t(1) << 20))
      ->capture_default_str();
  command.add_option("--limit", o.limits,
                     "Raise (or lower) a scene limit, counted before anything is built: particles, springs, "
                     "constraints, endpoints or entries (repeatable; defaults in docs/scenarios.md, Limits)")
      ->type_name("NAME=N")
      ->allow_extra_args(false);
}

// glibc gives the top of its heap back to the system once 128 KiB or more of it is free, and takes
// it again on the next frame: a render of the cloth made ~8 brk calls per frame, and with
// transparent huge pages each regrowth zeroes 2 MiB pages again (page faults were 10 % of the
// CPU time of `render -o cloth.mp4`, 5 % of its wall time, bench/README.md). Keeping up to 512 MiB
// of free heap, growing it 64 MiB at a time, and mapping only blocks of 32 MiB and more on their
// own ends the churn.
void keepHeapBetweenFrames() {
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  mallopt(M_TOP_PAD, 64 << 20);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
}

}  // namespace

int main(int argc, char** argv) {
  keepHeapBetweenFrames();
  CLI::App app{"particles: 2D particle systems and rigid bodies after Witkin & Baraff", "particles"};
  // The version, and on a second line the GL backend and renderer `render` would use.
  app.set_version_flag("--version",
                       [] { return "particles " PARTICLES_VERSION "\n" + particles::app::glVersionLine(); });
  app.require_subcommand(1);
  app.footer(
      "Exit codes: 0 success, 1 simulation failure (explosion; for compare: the frames differ),\n"
      "2 bad input or usage, 3 output failure.\n"
      "Run 'particles COMMAND --help' for the options of a command.\n");

  CommonOptions common;
  particles::app::RunOptions run;

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

  particles::app::RenderCommandOptions render;
  CLI::App* renderCmd =
      app.add_subcommand("render", "Simulate and draw the scenario off-screen to an MP4, PNG frames or one PNG");
  addCommonOptions(*renderCmd, common);
  renderCmd
      ->add_option("-o,--output", render.output, "file.mp4 (H.264), dir/ (frame_000000.png …) or file.png (with --at)")
      ->required();
  renderCmd->add_option("--at", render.at, "Draw the one frame at this simulated time, s (with -o file.png)");
  renderCmd->add_option("--frames", render.frames,
                        "Render frames A … B−1 only (A:B; A: to the end), each the same as in the whole render: "
                        "a segment of the video, or those frames of the sequence (join MP4 segments with concat)");
  renderCmd->add_option("--size", render.size, "Frame size WxH in px (default: the scenario's render.size)");
  renderCmd->add_option("--fps", render.fps, "Frames per simulated second (default: the scenario's render.fps)");
  renderCmd->add_option("--msaa", render.msaa, "Anti-aliasing samples per pixel: 1 (off), 2, 4, 8 or 16")
      ->check(CLI::IsMember(particles::render::kSampleCounts))
      ->capture_default_str();
  renderCmd
      ->add_option("--raster", render.raster,
                   "How shapes become pixels: triangles (one GL primitive each), tiles (sorted into screen tiles "
                   "on the CPU, one pass; fast for large scenes) or auto (tiles from 5000 shapes)")
      ->check(CLI::IsMember({"auto", "triangles", "tiles"}))
      ->capture_default_str();
  renderCmd->add_option("--theme", render.theme, "dark (screens) or light (printed reports)")->capture_default_str();
  renderCmd->add_option("--particle-radius", render.particleRadius,
                        "Particle disc radius: 4px (pixels) or 0.02m (world)");
  renderCmd->add_option("--crf", render.crf, "x264 constant rate factor, 0 (lossless) … 51")->capture_default_str();
  renderCmd
      ->add_option("--keyint", render.keyint,
                   "Longest time between keyframes, s (MP4): players seek to a keyframe, so shorter seeks faster")
      ->check(CLI::Range(1e-3, particles::render::kMaxKeyintSeconds))
      ->capture_default_str();
  renderCmd->add_option("--preset", render.preset, "x264 preset: ultrafast … veryslow")->capture_default_str();
  renderCmd->add_option("--png-level", render.pngLevel, "PNG compression level 0 … 9")->capture_default_str();
  renderCmd->add_flag("--verbose", render.verbose, "Name the GL backend and renderer; show libav/x264's own log");
  renderCmd
      ->add_option("--gl", render.gl,
                   fmt::format("GL backend: auto (EGL, else OSMesa), egl or osmesa (default: ${}, else auto)",
                               particles::app::kGlEnvironmentVariable))
      ->check(CLI::IsMember(particles::render::glBackendNames()));
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
      "Frame i shows t = i / fps; an MP4 has round(duration · fps) frames. Odd sizes are refused for MP4\n"
      "(H.264 yuv420p needs even sizes); PNG takes any size. Outputs appear only when complete.\n"
      "Frames are drawn by Mesa's llvmpipe on the CPU, the same bytes through EGL or OSMesa;\n"
      "'particles --version' names the backend and renderer.\n"
      "Examples:\n"
      "  particles render scenarios/cloth.yaml -o cloth.mp4\n"
      "  particles render scenarios/soft_body.yaml -o frames/ --size 640x360 --fps 30\n"
      "  particles render scenarios/cloth.yaml -o fig.png --at 2.5 --theme light --size 1600x1200\n"
      "  particles render scenarios/soft_body.yaml -o man.mp4 --hud   # time, integrator, dt, energy on every frame\n"
      "  particles render scenarios/rigid_chain.yaml -o chain.mp4 --crf 23 --preset veryfast --quiet\n"
      "  PARTICLES_GL=osmesa particles render scenarios/cloth.yaml -o cloth.mp4   # where EGL will not start\n");

  particles::app::StabilityOptionsCli stability;
  CLI::App* stabilityCmd = app.add_subcommand(
      "stability", "Find the largest stable time step of each integrator on a scenario (simulation only)");
  addCommonOptions(*stabilityCmd, common);
  stabilityCmd->add_option("--integrators", stability.integrators, "Integrators to study, comma-separated")
      ->delimiter(',')
      ->capture_default_str();
  stabilityCmd->add_option("--csv", stability.csv,
                           "Write integrator,evals_per_step,max_stable_dt,max_smooth_dt,cost_dt,evals_per_sim_second,"
                           "speed_vs_euler,wall_seconds_per_sim_second to this CSV");
  stabilityCmd->add_option("--plot", stability.plot, "Write the table as a bar chart (log axis): .svg or .png");
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
      "  particles stability scenarios/soft_body.yaml --integrators midpoint,rk4 --duration 20\n");

  particles::app::CompareOptions compare;
  CLI::App* compareCmd = particles::app::addCompareCommand(app, compare);

  particles::app::ConcatOptions concat;
  CLI::App* concatCmd = particles::app::addConcatCommand(app, concat);

  particles::app::PlotOptions plotOptions;
  CLI::App* plotCmd =
      app.add_subcommand("plot", "Draw the figure of a --stats CSV: energy and constraint error over time");
  plotCmd->add_option("stats", plotOptions.input, "A CSV written by run/render --stats")->required();
  plotCmd->add_option("-o,--output", plotOptions.output, "The figure: .svg (vector) or .png")->required();
  plotCmd->add_option("--title", plotOptions.title, "Title above the chart");
  plotCmd->add_option("--width", plotOptions.width, "Width in px (default 1200)")->check(CLI::Range(200, 10000));
  plotCmd->add_option("--height", plotOptions.height, "Height in px (default 800)")->check(CLI::Range(150, 10000));
  plotCmd->add_flag("-q,--quiet", plotOptions.quiet, "Print nothing on success");
  plotCmd->add_option("--max-input", plotOptions.maxInputMiB, "Refuse a CSV file larger than this, MiB")
      ->check(CLI::Range(std::uintmax_t(1), std::uintmax_t(1) << 20))
      ->capture_default_str();
  plotCmd->footer(
      "Examples:\n"
      "  particles run scenarios/cloth.yaml --stats cloth.csv && particles plot cloth.csv -o energy.svg\n"
      "  particles plot cloth.csv -o energy.png --title 'Cloth, RK4, dt = 0.01 s'\n");

  particles::app::SchemaOptions schema;
  CLI::App* schemaCmd = app.add_subcommand(
      "schema", "Print the scenario format as JSON Schema (draft 7), for editors and validators");
  schemaCmd->add_flag("--markdown", schema.markdown, "Print each kind's key table as docs/scenarios.md has it");
  schemaCmd->footer(
      "Examples:\n"
      "  particles schema > scenario.schema.json\n"
      "  # then, at the top of a scenario: # yaml-language-server: $schema=scenario.schema.json\n"
      "  particles schema --markdown\n");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);  // prints help, the version or the error
    return code == 0 ? particles::app::kOk : particles::app::kBadInput;
  }
  return particles::app::runReportingErrors({.scenario = common.scenario}, [&] {
    if (check->parsed()) return particles::app::checkCommand(common);
    if (schemaCmd->parsed()) return particles::app::schemaCommand(schema);
    if (stabilityCmd->parsed()) return particles::app::stabilityCommand(common, stability);
    if (plotCmd->parsed()) return particles::app::plotCommand(plotOptions);
    if (compareCmd->parsed()) return particles::app::compareCommand(compare);
    if (concatCmd->parsed()) return particles::app::concatCommand(concat);
    if (renderCmd->parsed()) return particles::app::renderCommand(common, render);
    return particles::app::runCommand(common, run);
  });
}
