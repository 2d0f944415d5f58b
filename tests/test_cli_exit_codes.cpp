// The program's one table from errors to exit codes and messages (src/app/exit_codes.hpp), seen
// from outside: for each kind of error, one command that meets it, its exit code and the whole of
// what it prints on stderr.
#include <doctest/doctest.h>

#include <filesystem>
#include <span>
#include <string>

#include "cli_support.hpp"

using namespace particles::test;

namespace {

// A stiff spring with explicit Euler at a huge step: blows up at step 5 (t = 0.5 s). Stiffer by
// 1000, even the stability study's reference run (rk4 at a quarter of dt) blows up.
std::string exploding(const std::string& ks) {
  return "name: boom\n"
         "simulation: {integrator: euler, dt: 0.1, duration: 10}\n"
         "render: {size: [64, 48], fps: 10}\n"
         "particles:\n"
         "  - {name: a, pos: [0, 0], fixed: true}\n"
         "  - {name: b, pos: [1.1, 0]}\n"
         "forces:\n"
         "  - {type: spring, a: a, b: b, rest: 1, ks: " +
         ks + "}\n";
}

struct Case {
  const char* args;
  int code;
  std::string err;  // all of stderr
};

// Runs each case and compares its exit code and the whole of its stderr.
void checkCases(Scratch& s, std::span<const Case> cases) {
  for (const Case& c : cases) {
    CAPTURE(c.args);
    const Result r = s.run(c.args);
    CHECK(r.code == c.code);
    CHECK(r.err == c.err);
  }
}

}  // namespace

TEST_CASE("cli exit codes: every kind of error has its code and its message format") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  s.write("boom.yaml", exploding("10000"));
  s.write("boom2.yaml", exploding("1e12"));  // ω = 10⁶ rad/s: RK4 explodes at dt / 256 too
  s.write("bad.yaml", "name: x\nsimulation:\n  dt: -1\n");
  s.write("bad.csv", "t,kinetic\n0,1\n");
  s.write("blocker", "a file where a directory should be");
  REQUIRE(s.run("run s.yaml --quiet --stats good.csv").code == 0);
  REQUIRE(s.run("render s.yaml -o a.png --at 0.5 --quiet").code == 0);
  // The core's words for the explosion, as `run` prints them after the scenario's name.
  const Result boom = s.run("run boom.yaml");
  const std::string head = "boom.yaml: error: ";
  REQUIRE(boom.err.rfind(head + "simulation exploded at step 5 (t = 0.5 s)", 0) == 0);
  REQUIRE(boom.err.back() == '\n');
  const std::string explosion = boom.err.substr(head.size(), boom.err.size() - head.size() - 1);

  const Case cases[] = {
      // 1: the simulation failed, named by the scenario file.
      {"run boom.yaml", 1, "boom.yaml: error: " + explosion + "\n"},
      {"render boom.yaml -o boom.png --at 5", 1, "boom.yaml: error: " + explosion + "\n"},
      {"render boom.yaml -o boom.mp4", 1,
       "boom.yaml: error: " + explosion + " (at frame 5 of 100; no output written)\n"},
      {"stability boom2.yaml --integrators rk4 --quiet", 1,
       "boom2.yaml: error: the reference run (rk4, dt = 0.000391 s) is itself unstable (exploded); give the scenario a "
       "smaller dt\n"},
      // 2: bad input or usage. The scenario loader's messages carry their own position.
      {"check bad.yaml", 2, "bad.yaml:3:7: error: simulation.dt: expected a number > 0, got -1\n"},
      {"render s.yaml -o out.mp4 --theme neon", 2, "error: --theme: expected dark or light, not 'neon'\n"},
      {"render s.yaml -o out.mp4 --size 65x48", 2,
       "error: MP4 (H.264, yuv420p) needs an even width and height; 65x48 is not (try 66x48, or write PNG frames)\n"},
      {"run s.yaml --stats x.csv --trace x.csv", 2,
       "error: --stats 'x.csv' and --trace 'x.csv' name the same file; an output never replaces another output\n"},
      {"plot good.csv -o out.txt", 2, "error: -o out.txt: a figure is .svg, .png or .pdf, not '.txt'\n"},
      {"stability s.yaml --integrators leapfrog", 2,
       "error: --integrators: unknown integrator 'leapfrog' (expected euler, midpoint, rk4, symplectic_euler, verlet, "
       "backward_euler or bdf2)\n"},
      {"plot bad.csv -o out.svg", 2,
       "error: bad.csv:1:10: the header must be exactly 't,kinetic,potential,total,constraint_error,penetration'\n"},
      {"compare a.png missing.png", 2, "error: cannot open missing.png: No such file or directory\n"},
      // 3: an output could not be made.
      {"run s.yaml --stats blocker/x.csv", 3, "error: cannot write blocker/x.csv: Not a directory\n"},
      {"render s.yaml -o blocker/frames/ --quiet", 3,
       "error: cannot create directory blocker/frames/: Not a directory\n"},
      {"compare a.png a.png --quiet --diff blocker/d.png", 3,
       "error: --diff: cannot write blocker/d.png: Not a directory\n"},
  };
  checkCases(s, cases);
}

// Numbers on the command line that were accepted silently (a fallback to the scenario's value, or
// t = 0 drawn for NaN) and a --set index that escaped as "internal error: stoull": all exit 2 now,
// naming the option.
TEST_CASE("cli exit codes: out-of-range, non-finite and empty option values are usage errors") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  const Case cases[] = {
      {"render s.yaml -o a.mp4 --fps 0", 2, "error: --fps: expected a whole number of frames per second from 1 to 1000, not 0\n"},
      {"render s.yaml -o a.mp4 --fps -5", 2, "error: --fps: expected a whole number of frames per second from 1 to 1000, not -5\n"},
      {"render s.yaml -o a.mp4 --fps nan", 2, "error: --fps: expected a whole number of frames per second from 1 to 1000, not nan\n"},
      {"render s.yaml -o a.png --at nan", 2, "error: --at: expected a simulated time in seconds, not nan\n"},
      {"check s.yaml --integrator ''", 2, "error: --integrator: expected a value, got an empty one\n"},
      {"check s.yaml --duration ''", 2, "error: --duration: expected a value, got an empty one\n"},
      {"stability s.yaml --max-dt nan", 2,
       "error: need --energy-tolerance > 0, --stretch-factor > 1, 0 < --shake-threshold ≤ 1 and 0 < --min-dt < "
       "--max-dt\n"},
      {"check s.yaml --set forces.99999999999999999999999.ks=1", 2,
       "s.yaml: error: forces.99999999999999999999999.ks (from --set forces.99999999999999999999999.ks=1): "
       "cannot use this key path: list index 99999999999999999999999 is too large\n"},
  };
  checkCases(s, cases);
  CHECK_FALSE(std::filesystem::exists(s.dir / "a.mp4"));
  CHECK_FALSE(std::filesystem::exists(s.dir / "a.png"));
}

// An endless input (/dev/zero) once grew memory without end; now a NUL byte ends the reading at
// once, a file past the input limit is refused from its size or as it is read, and --max-input
// raises the limit for scenes that are meant to be large.
TEST_CASE("cli exit codes: inputs past the input limit, endless ones included, are refused") {
  Scratch s;
  s.write("big.yaml", "name: big\n# " + std::string(2 * 1024 * 1024, 'x') + "\n");
  const Case cases[] = {
      {"check /dev/zero", 2, "/dev/zero: error: byte 1 is a NUL byte, which no text holds: this is not a text file\n"},
      {"plot /dev/zero -o z.svg", 2,
       "error: /dev/zero: byte 1 is a NUL byte, which no text holds: this is not a text file\n"},
      {"check /dev/stdin --max-input 1 < big.yaml", 2,
       "/dev/stdin: error: the file is larger than the input limit of 1 MiB; if it is meant to be, raise the limit "
       "with --max-input MIB\n"},
      {"check big.yaml --max-input 1", 2,
       "big.yaml: error: the file is larger than the input limit of 1 MiB; if it is meant to be, raise the limit "
       "with --max-input MIB\n"},
      {"check big.yaml --max-input 3 --quiet", 0, ""},
  };
  checkCases(s, cases);
}

// Scene limits are counted before anything is built; --limit raises (or lowers) one for a run.
TEST_CASE("cli exit codes: scene limits and --limit") {
  Scratch s;
  s.write("grid.yaml", "name: g\ngrids:\n  - {name: g, size: [30, 20]}\n");
  const Case cases[] = {
      {"check grid.yaml --quiet", 0, ""},
      {"check grid.yaml --limit particles=599", 2,
       "grid.yaml:3:21: error: grids[0].size: this makes 600 particles, more than the limit of 599 (counted before "
       "anything is built); if the scene is meant to be this large, raise the limit with --limit particles=N\n"},
      {"check grid.yaml --limit particles=599 --limit particles=600 --quiet", 0, ""},
      {"run grid.yaml --limit particle=5", 2,
       "command line: error: (--limit particle=5): unknown limit 'particle'; expected one of particles, springs, "
       "constraints, endpoints, entries, nodes\n"},
      {"stability grid.yaml --limit springs=-1", 2,
       "command line: error: (--limit springs=-1): expected a whole number from 1 to 1000000000 after '=', got "
       "'-1'\n"},
  };
  checkCases(s, cases);
}
