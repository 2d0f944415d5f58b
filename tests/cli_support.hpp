#pragma once
// Running the real `particles` program from tests: a scratch directory per test case and the
// program's exit code, stdout and stderr.
#include <doctest/doctest.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "sanitizer.hpp"

namespace particles::test {

namespace fs = std::filesystem;

// Built with AddressSanitizer (the program next to the tests is too): its shadow memory needs far
// more address space than any cap, and it slows and grows the run.
inline constexpr bool kSanitized = kUnderAddressSanitizer;

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

  // Runs `particles ARGS` in this directory, with the environment changed by `environment`: the
  // arguments of env(1), e.g. "-u PARTICLES_GL" or "PARTICLES_GL=osmesa".
  Result run(const std::string& args, const std::string& environment = "") const {
    const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
    REQUIRE_MESSAGE(fs::exists(exe), "the particles program is not built next to the tests: " << exe);
    const std::string command = "cd '" + dir.string() + "' && env " + environment + " '" + exe.string() + "' " + args +
                                " > stdout.txt 2> stderr.txt";
    return collect(std::system(command.c_str()));
  }

  // Starts `particles ARGS` here, waits until its output is open (the render is under way: a named
  // temporary in the folder, or an anonymous file, which /proc shows as "<folder>/#<inode>
  // (deleted)"), sends it `signal` ("INT", "TERM", "KILL") and returns its exit code and stderr.
  // SIGINT and SIGTERM are caught: the render stops and discards its output. SIGKILL cannot be
  // caught: the output is an anonymous O_TMPFILE file (PendingOutput), which vanishes with the process.
  Result interrupt(const std::string& args, const std::string& signal) const {
    const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
    const std::string command = "cd '" + dir.string() + "' && ('" + exe.string() + "' " + args +
                                " 2> stderr.txt & pid=$!; "
                                "for i in $(seq 100); do ls | grep -q partial && break; "
                                "ls -l /proc/$pid/fd | grep -qF \"$(pwd)/#\" && break; sleep 0.05; done; "
                                "kill -" +
                                signal + " $pid; wait $pid 2> /dev/null; echo $? > code.txt)";
    REQUIRE(std::system(command.c_str()) == 0);
    Result r;
    r.code = std::stoi(slurp(dir / "code.txt"));
    r.err = slurp(dir / "stderr.txt");
    fs::remove(dir / "code.txt");
    fs::remove(dir / "stderr.txt");
    return r;
  }

  // What a bounded run used: CPU seconds (user + system) and the program's peak resident memory.
  struct Usage {
    double cpuSeconds = 0;
    double peakMiB = 0;
  };

  // Runs `particles ARGS` as run() does, under guards that turn a hang or runaway memory into a
  // failed test instead of a stuck CI machine: address space capped at 2 GiB and a wall-clock
  // guard of 60 s after which the process is killed (code −1); no address-space cap under ASan.
  // Reports what the run used. `addressSpace` sets another cap, in bytes.
  Result runBounded(const std::string& args, Usage& usage, rlim_t addressSpace = rlim_t(2) << 30) const {
    const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
    REQUIRE_MESSAGE(fs::exists(exe), "the particles program is not built next to the tests: " << exe);
    const std::string command = "exec '" + exe.string() + "' " + args + " > stdout.txt 2> stderr.txt";
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      const rlimit memory{addressSpace, addressSpace};
      if (::chdir(dir.c_str()) != 0 || (!kSanitized && ::setrlimit(RLIMIT_AS, &memory) != 0)) ::_exit(127);
      ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    int status = 0;
    rusage used{};
    // The peak is the program's own high-water mark (VmHWM, kB), read while the child runs it: not
    // wait4's ru_maxrss, in which Linux keeps the child's memory from before exec, a copy of this
    // test process's (fork), and that was 397 MiB after the test cases before this one in the
    // same process. VmHWM only grows, so the last reading is the peak but for the last 5 ms.
    const fs::path program = fs::canonical(exe);
    const std::string proc = "/proc/" + std::to_string(pid);
    double peakKiB = 0;
    const auto readPeak = [&] {
      std::error_code ec;
      if (fs::read_symlink(proc + "/exe", ec) != program) return;  // not yet exec'd, or gone
      std::ifstream statusFile(proc + "/status");
      for (std::string line; std::getline(statusFile, line);) {
        if (line.rfind("VmHWM:", 0) == 0) peakKiB = std::max(peakKiB, std::atof(line.c_str() + 6));
      }
    };
    const auto start = std::chrono::steady_clock::now();
    for (readPeak(); ::wait4(pid, &status, WNOHANG, &used) == 0; readPeak()) {
      if (std::chrono::steady_clock::now() - start > std::chrono::seconds(60)) {
        ::kill(pid, SIGKILL);
        ::wait4(pid, &status, 0, &used);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    usage.cpuSeconds = double(used.ru_utime.tv_sec + used.ru_stime.tv_sec) +
                       1e-6 * double(used.ru_utime.tv_usec + used.ru_stime.tv_usec);
    usage.peakMiB = peakKiB / 1024.0;
    return collect(status);
  }

 private:
  // The exit code from a wait status (−1 when killed), and the output files, which are removed.
  Result collect(int status) const {
    Result r;
    r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    r.out = slurp(dir / "stdout.txt");
    r.err = slurp(dir / "stderr.txt");
    fs::remove(dir / "stdout.txt");
    fs::remove(dir / "stderr.txt");
    return r;
  }
};

// Runs `particles ARGS` in `s` as bad input: exit 2, with a message naming `option`.
inline void checkRefused(const Scratch& s, const std::string& args, const std::string& option) {
  CAPTURE(args);
  const Result r = s.run(args);
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.find(option) != std::string::npos, r.err);
}

// What a shell command prints on stdout, and whether it exited 0.
inline std::string commandOutput(const std::string& command, bool& succeeded) {
  FILE* pipe = ::popen(command.c_str(), "r");
  REQUIRE_MESSAGE(pipe != nullptr, "popen " << command);
  std::string text;
  char buffer[4096];
  for (size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) text.append(buffer, n);
  succeeded = ::pclose(pipe) == 0;
  return text;
}

// The presentation times of the keyframes of `video`, in seconds, from ffprobe's packet list
// (flags "K" mark a keyframe).
inline std::vector<double> keyframeTimes(const fs::path& video) {
  bool succeeded = false;
  const std::string text = commandOutput(
      "ffprobe -v error -select_streams v:0 -show_entries packet=pts_time,flags -of csv=p=0 '" + video.string() + "'",
      succeeded);
  REQUIRE_MESSAGE(succeeded, "ffprobe failed on " << video << " (scripts/deps installs ffmpeg)");
  std::vector<double> times;
  for (const std::string& line : lines(text)) {
    const size_t comma = line.find(',');
    if (comma != std::string::npos && line.find('K', comma) != std::string::npos) {
      times.push_back(std::stod(line.substr(0, comma)));
    }
  }
  std::sort(times.begin(), times.end());  // packets come in decoding order
  return times;
}

// The longest time from a keyframe to the next one or to the end of a video `duration` s long:
// what a player may have to decode to reach a point.
inline double longestKeyframeGap(const std::vector<double>& keyframes, double duration) {
  REQUIRE(!keyframes.empty());
  CHECK(keyframes.front() == 0.0);
  double longest = duration - keyframes.back();
  for (size_t i = 1; i < keyframes.size(); ++i) longest = std::max(longest, keyframes[i] - keyframes[i - 1]);
  return longest;
}

// The files a command left in the scratch folder besides its scenario (s.yaml), sorted.
inline std::vector<std::string> outputs(const Scratch& s) {
  auto files = s.files();
  files.erase(std::remove(files.begin(), files.end(), "s.yaml"), files.end());
  std::sort(files.begin(), files.end());
  return files;
}

// Whether `text` holds `part`.
inline bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Whether the loader's own account of a run (LD_DEBUG=libs, on stderr) says it started `library`
// ("calling init: PATH"): which libraries a command loads, and which it does not.
inline bool loaderStarted(const std::string& loaderLog, const std::string& library) {
  for (const std::string& line : lines(loaderLog)) {
    if (contains(line, "calling init: ") && contains(line, library)) return true;
  }
  return false;
}

// The most memory a command of the CLI tests may peak at (getrusage), where no sanitizer runs.
inline constexpr double kMaxPeakMiB = 200.0;

}  // namespace particles::test
