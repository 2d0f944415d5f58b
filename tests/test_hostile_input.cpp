// Inputs that once hung the program, ate memory without end, crashed with "internal error" or
// were accepted silently. Each now ends in a clear message and its exit code (2 bad input, 3
// output; 0 where the input is valid after all), using at most 2 s of CPU and 200 MiB of memory,
// printing no crash text and leaving no file behind. The runs are guarded (2 GiB of address space,
// 60 s of wall time) so that a regression fails instead of hanging the machine. Under the
// sanitizers the resource bounds are not checked: ASan's shadow memory and slowdown are not the
// program's.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <thread>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_support.hpp"

using namespace particles::test;

namespace {

constexpr double kMaxCpuSeconds = 2.0;

std::vector<std::string> sorted(std::vector<std::string> names) {
  std::sort(names.begin(), names.end());
  return names;
}

struct Row {
  std::string args;
  int code;
  std::string err;  // the start of stderr (all of it when `whole`)
  bool whole = true;
};

// Runs each row in `s` and checks its code, its message, its cost and that the folder holds the
// same files afterwards (plus `made`, the outputs a successful row is meant to write).
void checkRows(Scratch& s, const std::vector<Row>& rows, const std::vector<std::string>& made = {}) {
  const std::vector<std::string> before = sorted(s.files());
  for (const Row& row : rows) {
    CAPTURE(row.args);
    Scratch::Usage usage;
    const Result r = s.runBounded(row.args, usage);
    CHECK(r.code == row.code);
    if (row.whole) {
      CHECK(r.err == row.err);
    } else {
      CHECK(r.err.rfind(row.err, 0) == 0);
      CAPTURE(r.err);
    }
    CHECK(r.err.size() < 400);  // a message, not an echo of the input
    CHECK(r.err.find("internal error") == std::string::npos);
    CHECK(r.err.find("terminate") == std::string::npos);
    REQUIRE(usage.peakMiB > 1.0);  // the measurement itself works (a program needs more than 1 MiB)
    if (!kSanitized) {
      CHECK(usage.cpuSeconds <= kMaxCpuSeconds);
      CHECK(usage.peakMiB <= kMaxPeakMiB);
    }
    std::vector<std::string> after = s.files();
    for (const std::string& m : made) std::erase(after, m);
    CHECK(sorted(after) == before);
    for (const std::string& m : made) std::filesystem::remove(s.dir / m);
  }
}

}  // namespace

TEST_CASE("hostile input: a one-byte scenario ',' on which yaml-cpp's LoadAll never returns") {
  Scratch s;
  s.write("comma.yaml", ",");
  s.write("t4.yaml", ",t4");
  checkRows(s, {{"check comma.yaml", 2,
                 "comma.yaml:1:1: error: YAML syntax error: cannot read on from here (a stray ',' or bracket?)\n"},
                {"run t4.yaml", 2,
                 "t4.yaml:1:1: error: YAML syntax error: cannot read on from here (a stray ',' or bracket?)\n"}});
}

TEST_CASE("hostile input: plot on stats spanning ±1e308 (the tick loop never ended)") {
  Scratch s;
  std::string csv = "t,kinetic,potential,total,constraint_error,penetration\n";
  const double values[] = {1e308, -1e308, 0.0, 1.7e308, -1.7e308};
  for (int i = 0; i < 5; ++i) csv += fmt::format("{},{},{},{},0,0\n", 0.1 * i, values[i], -values[i], values[i]);
  s.write("wide.csv", csv);
  // Valid data: a figure, not an error.
  checkRows(s, {{"plot wide.csv -o wide.svg --quiet", 0, ""}}, {"wide.svg"});
}

TEST_CASE("hostile input: a few hundred bytes that expand to gigabytes of springs") {
  Scratch s;
  std::string refs;
  for (int i = 0; i < 200; ++i) refs += i ? ", g" : "g";
  s.write("many.yaml", "name: big\ngrids:\n  - {name: g, size: [1000, 1000]}\nforces:\n  - {type: spring, a: [" +
                           refs + "], b: [" + refs + "], ks: 1}\n");
  std::string aliases =
      "name: big\nparticles:\n  - {name: p, pos: [0, 1]}\ngrids:\n  - {name: g, size: [1000, 999]}\n"
      "forces:\n  - &s {type: spring, a: g, b: p, ks: 1}\n";
  for (int i = 0; i < 60; ++i) aliases += "  - *s\n";
  s.write("aliases.yaml", aliases);
  checkRows(s, {{"check many.yaml", 2,
                 "many.yaml:5:23: error: forces[0].a: this makes 200000000 points named by references, more than the "
                 "limit of 16000000 (counted before anything is built); if the scene is meant to be this large, raise "
                 "the limit with --limit endpoints=N\n"},
                {"render aliases.yaml -o a.mp4", 2,
                 "aliases.yaml:7:5: error: forces[8]: this makes 8991000 springs and forces in the scene so far, more "
                 "than the limit of 8000000 (counted before anything is built); if the scene is meant to be this "
                 "large, raise the limit with --limit springs=N\n"}});
}

TEST_CASE("hostile input: --stats /dev/null (once replaced by a regular file when run as root)") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  checkRows(s, {{"run s.yaml --quiet --stats /dev/null", 0, ""}, {"run s.yaml --quiet --trace /dev/null", 0, ""}});
  struct stat devNull {};
  REQUIRE(::lstat("/dev/null", &devNull) == 0);
  CHECK(S_ISCHR(devNull.st_mode));
}

TEST_CASE("hostile input: kill -9 during render -o x.mp4 leaves no file behind") {
  Scratch s;
  // 600 simulated seconds at 30 fps: about 10 s of rendering (600 frames of it took 0.4 s), killed
  // after half a second.
  std::string longer = kSwingScenario;
  longer.replace(longer.find("duration: 1"), 11, "duration: 600");
  longer.replace(longer.find("fps: 10"), 7, "fps: 30");
  s.write("s.yaml", longer);
  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(s.dir.c_str()) != 0) ::_exit(127);
    ::execl(exe.c_str(), "particles", "render", "s.yaml", "-o", "x.mp4", "--quiet", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  int status = 0;
  const bool stillRunning = ::waitpid(pid, &status, WNOHANG) == 0;
  ::kill(pid, SIGKILL);
  if (stillRunning) ::waitpid(pid, &status, 0);
  REQUIRE_MESSAGE(stillRunning, "the render ended before it could be killed; make the scenario longer");
  CHECK(WIFSIGNALED(status));
  CHECK(s.files() == std::vector<std::string>{"s.yaml"});
}

TEST_CASE("hostile input: a 65-byte PNG whose header claims 100000 × 100000 pixels") {
  Scratch s;
  const std::filesystem::path fixtures = std::filesystem::path(PARTICLES_SOURCE_DIR) / "tests/fixtures";
  for (const char* name : {"png_header_100000x100000.png", "png_header_20000x20000.png"}) {
    std::filesystem::copy_file(fixtures / name, s.dir / name);
  }
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o a.png --at 0 --quiet").code == 0);
  checkRows(s, {{"compare a.png png_header_100000x100000.png", 2,
                 "error: png_header_100000x100000.png: its header claims 100000x100000 pixels; images are at most "
                 "16384 pixels a side\n"},
                {"compare png_header_20000x20000.png a.png --diff d.png", 2,
                 "error: png_header_20000x20000.png: its header claims 20000x20000 pixels; images are at most 16384 "
                 "pixels a side\n"}});
}

TEST_CASE("hostile input: a --set index past size_t, and numbers that were accepted silently") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  const std::string fps = "error: --fps: expected a whole number of frames per second from 1 to 1000, not ";
  checkRows(s, {{"check s.yaml --set forces.99999999999999999999999.ks=1", 2,
                 "s.yaml: error: forces.99999999999999999999999.ks (from --set forces.99999999999999999999999.ks=1): "
                 "cannot use this key path: list index 99999999999999999999999 is too large\n"},
                {"render s.yaml -o a.mp4 --fps 0", 2, fps + "0\n"},
                {"render s.yaml -o a.mp4 --fps -5", 2, fps + "-5\n"},
                {"render s.yaml -o a.mp4 --fps nan", 2, fps + "nan\n"},
                {"render s.yaml -o a.png --at nan", 2, "error: --at: expected a simulated time in seconds, not nan\n"},
                {"run s.yaml --integrator ''", 2, "error: --integrator: expected a value, got an empty one\n"}});
}

TEST_CASE("hostile input: /dev/zero as a scenario or a stats CSV") {
  Scratch s;
  checkRows(s, {{"check /dev/zero", 2, "/dev/zero: error: byte 1 is a NUL byte, which no text holds: this is not a text "
                                       "file\n"},
                {"plot /dev/zero -o z.svg", 2,
                 "error: /dev/zero: byte 1 is a NUL byte, which no text holds: this is not a text file\n"}});
}

TEST_CASE("hostile input: a CSV field of 10 MB that is not a number is quoted by 80 bytes") {
  Scratch s;
  s.write("huge.csv", "t,kinetic,potential,total,constraint_error,penetration\n0," + std::string(10'000'000, 'x') +
                          ",0,0,0,0\n");
  checkRows(s, {{"plot huge.csv -o h.svg", 2,
                 "error: huge.csv:2:3: column 'kinetic': expected a number, found '" + std::string(72, 'x') +
                     "…' (10000000 bytes)\n"}});
}
