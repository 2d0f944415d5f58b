// The `particles` program end to end (docs/physics.md §12): exit codes, summaries, the --stats and --trace
// CSVs, and that a failed run leaves no output behind. Runs the binary built next to this test.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_support.hpp"

using namespace particles::test;
namespace fs = std::filesystem;

namespace {

const std::string kPendulum =
    "name: pendulum\n"
    "simulation: {integrator: rk4, dt: 0.01, duration: 1}\n"
    "render: {fps: 10}\n"
    "particles:\n"
    "  - {name: pivot, pos: [0, 0], fixed: true}\n"
    "  - {name: bob, pos: [1, 0]}\n"
    "rigid_bodies:\n"
    "  - {name: box, pos: [3, 0], size: [1, 1], omega: 2}\n"
    "forces:\n"
    "  - {type: gravity}\n"
    "constraints:\n"
    "  - {type: rod, a: pivot, b: bob}\n";

// A stiff spring with explicit Euler at a huge step: blows up in a few steps.
const std::string kExploding =
    "name: boom\n"
    "simulation: {integrator: euler, dt: 0.1, duration: 10}\n"
    "particles:\n"
    "  - {name: a, pos: [0, 0], fixed: true}\n"
    "  - {name: b, pos: [1.1, 0]}\n"
    "forces:\n"
    "  - {type: spring, a: a, b: b, rest: 1, ks: 10000}\n";

}  // namespace

TEST_CASE("cli: --version and --help") {
  Scratch s;
  Result r = s.run("--version");
  CHECK(r.code == 0);
  CHECK(r.out.find("particles 0.") != std::string::npos);
  r = s.run("--help");
  CHECK(r.code == 0);
  // The Subcommands section lists every command once, by its name, and only those: one line each,
  // "  NAME   summary", up to the blank line that ends it.
  const std::vector<std::string> commands = {"check", "run",    "render", "stability", "compare", "concat",
                                             "plot",  "schema", "sweep",  "gather",    "job",     "golden"};
  std::vector<std::string> listed;
  std::istringstream help(r.out);
  std::string line;
  while (std::getline(help, line) && line != "Subcommands:") {
  }
  while (std::getline(help, line) && !line.empty()) {
    CAPTURE(line);
    CHECK(line.starts_with("  "));
    std::istringstream words(line);
    std::string name, summary;
    words >> name;
    std::getline(words >> std::ws, summary);
    CHECK_FALSE(summary.empty());
    listed.push_back(name);
  }
  CAPTURE(r.out);
  const auto sortedNames = [](std::vector<std::string> names) {
    std::sort(names.begin(), names.end());
    return fmt::format("{}", fmt::join(names, " "));
  };
  CHECK(sortedNames(listed) == sortedNames(commands));
  // Each name listed is a command: its own help, under its own name.
  for (const std::string& command : listed) {
    CAPTURE(command);
    const Result own = s.run(command + " --help");
    CHECK(own.code == 0);
    CHECK(own.out.find("Usage: particles " + command + " ") != std::string::npos);
  }
  CHECK(r.out.find("Exit codes") != std::string::npos);
  for (const char* command : {"check", "run"}) {
    CAPTURE(command);
    r = s.run(std::string(command) + " --help");
    CHECK(r.code == 0);
    CHECK(r.out.find("Examples:") != std::string::npos);
    CHECK(r.out.find("--set") != std::string::npos);
  }
}

TEST_CASE("cli: usage errors exit with 2") {
  Scratch s;
  CHECK(s.run("").code == 2);
  CHECK(s.run("frobnicate x.yaml").code == 2);
  CHECK(s.run("run").code == 2);
  s.write("p.yaml", kPendulum);
  CHECK(s.run("run p.yaml --no-such-option").code == 2);
  const Result r = s.run("run p.yaml --trace-only bob");  // --trace-only needs --trace
  CHECK(r.code == 2);
}

// CLI11 alone answered `particles golden --help` (before golden was a command) with the main help and exit 0, as if the
// word were not there: a typo in a script went unnoticed.
TEST_CASE("cli: an unknown command is a usage error naming it, with or without --help") {
  Scratch s;
  for (const std::string args :
       {"frobnicate --help", "frobnicate", "--help frobnicate", "frobnicate x.yaml -o x.mp4"}) {
    CAPTURE(args);
    const Result r = s.run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());  // no help
    CHECK_MESSAGE(r.err.starts_with("unknown command 'frobnicate'; the commands are check, run, render, "), r.err);
  }
  // A near miss names the command meant.
  for (const std::string args : {"rnder --help", "rnder x.yaml -o x.mp4", "stabilty x.yaml"}) {
    CAPTURE(args);
    const Result r = s.run(args);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    const std::string word = args.substr(0, args.find(' '));
    const std::string meant = word == "rnder" ? "render" : "stability";
    CHECK_MESSAGE(r.err.starts_with(fmt::format("unknown command '{}' (did you mean '{}'?)", word, meant)), r.err);
  }
}

TEST_CASE("cli: check accepts a valid scenario and rejects a bad one with file, line and key") {
  Scratch s;
  s.write("p.yaml", kPendulum);
  Result r = s.run("check p.yaml");
  CHECK(r.code == 0);
  CHECK(r.out.find("ok") != std::string::npos);
  CHECK(r.out.find("2 particles") != std::string::npos);

  s.write("bad.yaml", "name: x\nsimulation:\n  dt: -1\n");
  r = s.run("check bad.yaml");
  CHECK(r.code == 2);
  CHECK(r.err.find("bad.yaml:3:") != std::string::npos);
  CHECK(r.err.find("simulation.dt") != std::string::npos);

  r = s.run("check missing.yaml");
  CHECK(r.code == 2);
  CHECK(r.err.find("missing.yaml") != std::string::npos);

  r = s.run("check p.yaml --set simulation.dt=0");
  CHECK(r.code == 2);
  CHECK(r.err.find("--set simulation.dt=0") != std::string::npos);
  CHECK(s.run("check p.yaml --integrator rk5").code == 2);
  CHECK(s.run("check p.yaml --set nodot").code == 2);
}

TEST_CASE("cli: run prints a summary and writes the stats and trace CSVs") {
  Scratch s;
  s.write("p.yaml", kPendulum);
  const Result r = s.run("run p.yaml --stats stats.csv --trace trace.csv");
  REQUIRE(r.code == 0);
  CHECK(r.err.empty());  // no progress when stderr is not a terminal
  for (const char* field : {"particles", "springs", "constraints", "integrator", "dt", "steps", "wall time",
                            "sim/wall ratio", "final energy", "constraint error", "penetration"}) {
    CAPTURE(field);
    CHECK(r.out.find(field) != std::string::npos);
  }
  CHECK(r.out.find("100") != std::string::npos);  // steps

  const auto stats = lines(slurp(s.dir / "stats.csv"));
  REQUIRE(stats.size() == 1 + 11);  // header, t = 0, 0.1, …, 1.0
  CHECK(stats[0] == "t,kinetic,potential,total,constraint_error,penetration");
  CHECK(stats[1].rfind("0,", 0) == 0);
  CHECK(stats.back().rfind("1,", 0) == 0);

  const auto trace = lines(slurp(s.dir / "trace.csv"));
  REQUIRE(trace.size() == 1 + 11 * 3);
  CHECK(trace[0] == "t,name,x,y,vx,vy,angle,omega");
  CHECK(trace[1] == "0,pivot,0,0,0,0,0,0");
  CHECK(trace[2] == "0,bob,1,0,0,0,0,0");
  CHECK(trace[3] == "0,box,3,0,0,0,0,2");

  // Full precision: fmt's shortest round-trip form, so energies carry ~17 significant digits.
  std::istringstream row(stats[5]);
  std::string cell;
  int cells = 0;
  size_t longest = 0;
  while (std::getline(row, cell, ',')) {
    ++cells;
    CHECK_NOTHROW((void)std::stod(cell));
    longest = std::max(longest, cell.size());
  }
  CHECK(longest >= 15);
  CHECK(cells == 6);

  // Only what was written: no temporary files left behind.
  auto files = s.files();
  std::sort(files.begin(), files.end());
  CHECK(files == std::vector<std::string>{"p.yaml", "stats.csv", "trace.csv"});
}

TEST_CASE("cli: CSV times are the tick times i / fps exactly, or the step's time without k · dt's rounding") {
  Scratch s;
  const std::string springs = std::string(PARTICLES_SOURCE_DIR) + "/scenarios/springs.yaml";
  const auto times = [&](const std::string& file) { return lines(slurp(s.dir / file)); };
  // Ten steps per tick at 60 fps: every row is at a tick, and its time reads back as i / 60 exactly,
  // where 10 · k · dt accumulates rounding (e.g. 0.05 is 30 · 0.0016666666666666668 = 0.05000000000000001).
  REQUIRE(s.run("run " + springs + " --dt 0.0016666666666666668 --duration 2 --quiet --stats a.csv --trace b.csv "
                "--trace-only mass_a").code == 0);
  for (const char* file : {"a.csv", "b.csv"}) {
    CAPTURE(file);
    const auto rows = times(file);
    REQUIRE(rows.size() == 1 + 121);
    CHECK(rows[0].rfind("t,", 0) == 0);  // the header as before
    for (size_t i = 1; i < rows.size(); ++i) {
      CAPTURE(rows[i]);
      CHECK(std::stod(rows[i].substr(0, rows[i].find(','))) == double(i - 1) / 60.0);
    }
  }
  // Steps of 0.07 s between ticks: the times are the steps' as written in decimals, 0.21, not the
  // 0.21000000000000002 that 3 · 0.07 gives.
  REQUIRE(s.run("run " + springs + " --dt 0.07 --duration 1.4 --quiet --stats c.csv").code == 0);
  const auto rows = times("c.csv");
  REQUIRE(rows.size() == 1 + 21);
  CHECK(rows[4].rfind("0.21,", 0) == 0);
  for (size_t i = 1; i < rows.size(); ++i) {
    CAPTURE(rows[i]);
    const std::string t = rows[i].substr(0, rows[i].find(','));
    CHECK(t == fmt::format("{}", std::round((i - 1) * 7.0) / 100));  // the nearest double to (i − 1) · 0.07
  }
}

TEST_CASE("cli: runs are deterministic") {
  Scratch s;
  s.write("p.yaml", kPendulum);
  REQUIRE(s.run("run p.yaml --quiet --stats a.csv --trace ta.csv").code == 0);
  REQUIRE(s.run("run p.yaml --quiet --stats b.csv --trace tb.csv").code == 0);
  CHECK(slurp(s.dir / "a.csv") == slurp(s.dir / "b.csv"));
  CHECK(slurp(s.dir / "ta.csv") == slurp(s.dir / "tb.csv"));
}

TEST_CASE("cli: --trace-only, --quiet and the shorthands") {
  Scratch s;
  s.write("p.yaml", kPendulum);
  Result r = s.run("run p.yaml --quiet --trace t.csv --trace-only bob,box --dt 0.005 --duration 0.5");
  REQUIRE(r.code == 0);
  CHECK(r.out.empty());
  CHECK(r.err.empty());
  const auto trace = lines(slurp(s.dir / "t.csv"));
  REQUIRE(trace.size() == 1 + 6 * 2);
  CHECK(trace[1].rfind("0,bob,", 0) == 0);
  CHECK(trace[2].rfind("0,box,", 0) == 0);
  CHECK(trace.back().rfind("0.5,box,", 0) == 0);

  r = s.run("run p.yaml --trace t2.csv --trace-only nobody");
  CHECK(r.code == 2);
  CHECK(r.err.find("nobody") != std::string::npos);
  CHECK(!fs::exists(s.dir / "t2.csv"));

  r = s.run("run p.yaml --integrator euler --set simulation.duration=0.1");
  CHECK(r.code == 0);
  CHECK(r.out.find("euler") != std::string::npos);
}

TEST_CASE("cli: bad input writes nothing and exits with 2") {
  Scratch s;
  s.write("bad.yaml", "name: x\nparticles:\n  - {pos: [0, 0], mass: -1}\n");
  const Result r = s.run("run bad.yaml --stats stats.csv --trace trace.csv");
  CHECK(r.code == 2);
  CHECK(r.err.find("bad.yaml:3:") != std::string::npos);
  CHECK(r.err.find("particles[0].mass") != std::string::npos);
  CHECK(s.files() == std::vector<std::string>{"bad.yaml"});
}

TEST_CASE("cli: an explosion prints the simulation error, exits with 1 and removes the outputs") {
  Scratch s;
  s.write("boom.yaml", kExploding);
  const Result r = s.run("run boom.yaml --stats stats.csv --trace trace.csv");
  CHECK(r.code == 1);
  CHECK(r.err.find("exploded") != std::string::npos);
  CHECK(s.files() == std::vector<std::string>{"boom.yaml"});
}

TEST_CASE("cli: an unwritable output exits with 3 and leaves nothing") {
  Scratch s;
  s.write("p.yaml", kPendulum);
  Result r = s.run("run p.yaml --stats no/such/dir/stats.csv");
  CHECK(r.code == 3);
  CHECK(r.err.find("no/such/dir/stats.csv") != std::string::npos);
  r = s.run("run p.yaml --stats ok.csv --trace .");  // a directory
  CHECK(r.code == 3);
  CHECK(s.files() == std::vector<std::string>{"p.yaml"});
}
