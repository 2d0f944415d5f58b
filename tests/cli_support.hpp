#pragma once
// Running the real `particles` program from tests: a scratch directory per test case and the
// program's exit code, stdout and stderr.
#include <doctest/doctest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace particles::test {

namespace fs = std::filesystem;

struct Result {
  int code = -1;
  std::string out, err;
};

inline std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// A rod pendulum for 1 s at 10 fps, drawn at 160 × 120.
inline const std::string kSwingScenario =
    "name: swing\n"
    "simulation: {integrator: rk4, dt: 0.01, duration: 1}\n"
    "render: {size: [160, 120], fps: 10, view: {center: [0, -0.5], height: 3}}\n"
    "particles:\n"
    "  - {name: pivot, pos: [0, 0], fixed: true}\n"
    "  - {name: bob, pos: [1, 0]}\n"
    "forces:\n"
    "  - {type: gravity}\n"
    "constraints:\n"
    "  - {type: rod, a: pivot, b: bob}\n";

// A scratch directory per test case, removed afterwards. mkdtemp: a fresh directory of our own,
// never one that happens to exist already.
struct Scratch {
  fs::path dir;
  Scratch() {
    std::string pattern = (fs::temp_directory_path() / "particles_cli_test_XXXXXX").string();
    REQUIRE_MESSAGE(::mkdtemp(pattern.data()) != nullptr, "mkdtemp " << pattern << ": " << std::strerror(errno));
    dir = pattern;
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name) << text;
    return dir / name;
  }
  std::vector<std::string> files() const {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    return out;
  }

  // Runs `particles ARGS` in this directory.
  Result run(const std::string& args) const {
    const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
    REQUIRE_MESSAGE(fs::exists(exe), "the particles program is not built next to the tests: " << exe);
    const std::string command =
        "cd '" + dir.string() + "' && '" + exe.string() + "' " + args + " > stdout.txt 2> stderr.txt";
    const int status = std::system(command.c_str());
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir / "stdout.txt");
    r.err = slurp(dir / "stderr.txt");
    fs::remove(dir / "stdout.txt");
    fs::remove(dir / "stderr.txt");
    return r;
  }
};

}  // namespace particles::test
