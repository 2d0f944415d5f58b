// `particles sweep` and `particles gather` (docs/sweeps.md), through the real program: a sweep file
// expanded into jobs, bad sweep files refused before any job runs, jobs run here with failures
// listed, a killed sweep resumed without running a finished job again, and a render split into
// segments and joined. GNU parallel and Slurm run the emitted lists in tests/sweep/ (CTest);
// hostile sweep files and tampered sweep folders are test_sweep_hostile.cpp's.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

#include "input/available_cores.hpp"
#include "cli_support.hpp"
#include "support/video_probe.hpp"
#include "source_tree.hpp"

using particles::test::kSource;

namespace {

using particles::test::lines;
using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;


// Splits a CSV line without quoted commas (the tests' own tables have none outside `command`).
std::vector<std::string> fields(const std::string& line) {
  std::vector<std::string> out;
  std::string field;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      out.push_back(field);
      field.clear();
    } else {
      field += c;
    }
  }
  out.push_back(field);
  return out;
}

// The rows of a CSV as maps from column name to value.
std::vector<std::map<std::string, std::string>> table(const fs::path& csv) {
  const auto text = lines(slurp(csv));
  REQUIRE(!text.empty());
  const auto header = fields(text[0]);
  std::vector<std::map<std::string, std::string>> rows;
  for (size_t i = 1; i < text.size(); ++i) {
    const auto f = fields(text[i]);
    REQUIRE_MESSAGE(f.size() == header.size(), csv << " line " << i + 1);
    std::map<std::string, std::string> row;
    for (size_t k = 0; k < f.size(); ++k) row[header[k]] = f[k];
    rows.push_back(row);
  }
  return rows;
}

// Three damped springs; a run of 0.5 s takes milliseconds.
const std::string kSpringsSweep =
    "scenarios: [" + kSource + "/scenarios/springs.yaml]\n"
    "command: run\n"
    "options: {duration: 0.5}\n"
    "parameters:\n"
    "  - key: forces[1].ks\n"
    "    values: [20, 50, 80]\n"
    "  - zip:\n"
    "    - {key: integrator, values: [euler, rk4]}\n"
    "    - {key: dt, values: [0.001, 0.01]}\n";

// A job's folder name: jobs/000007.
std::string jobDir(int index) {
  char name[16];
  std::snprintf(name, sizeof name, "%06d", index);
  return name;
}

}  // namespace

TEST_CASE("sweep: the parameters crossed and zipped, one plain command line per job in jobs.csv") {
  Scratch s;
  s.write("springs.yaml", kSpringsSweep);
  const auto r = s.run("sweep springs.yaml -o out --emit parallel");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto jobs = table(s.dir / "out/jobs.csv");
  REQUIRE(jobs.size() == 6);  // 3 stiffnesses × 2 zipped pairs
  const std::vector<std::array<std::string, 3>> expected = {{"20", "euler", "0.001"}, {"20", "rk4", "0.01"},
                                                            {"50", "euler", "0.001"}, {"50", "rk4", "0.01"},
                                                            {"80", "euler", "0.001"}, {"80", "rk4", "0.01"}};
  const auto list = lines(slurp(s.dir / "out/jobs.txt"));
  REQUIRE(list.size() == 6);
  for (size_t i = 0; i < jobs.size(); ++i) {
    CAPTURE(i);
    CHECK(jobs[i].at("index") == std::to_string(i));
    CHECK(jobs[i].at("stage") == "run");
    CHECK(jobs[i].at("forces[1].ks") == expected[i][0]);
    CHECK(jobs[i].at("integrator") == expected[i][1]);
    CHECK(jobs[i].at("dt") == expected[i][2]);
    const std::string& command = jobs[i].at("command");
    CHECK(command.find(" run " + kSource + "/scenarios/springs.yaml --duration 0.5 ") != std::string::npos);
    CHECK(command.find("--set 'forces[1].ks=" + expected[i][0] + "'") != std::string::npos);
    CHECK(command.find("--integrator " + expected[i][1] + " --dt " + expected[i][2]) != std::string::npos);
    CHECK(command.find("--stats " + (s.dir / "out" / jobs[i].at("dir") / "stats.csv").string()) != std::string::npos);
    CHECK(command.find("--record " + (s.dir / "out" / jobs[i].at("dir") / "record.txt").string()) != std::string::npos);
    // The list names the job; its command line stays in jobs.csv, never passed to a shell.
    CHECK(list[i] == fs::read_symlink("/proc/self/exe").parent_path().string() + "/particles job " +
                         (s.dir / "out").string() + " " + std::to_string(i));
    CHECK(fs::is_directory(s.dir / "out" / jobs[i].at("dir")));
  }
  CHECK_FALSE(fs::exists(s.dir / "out/results.csv"));  // emitted, not run

  const auto slurm = s.run("sweep springs.yaml -o out --emit slurm");
  REQUIRE_MESSAGE(slurm.code == 0, slurm.err);
  const std::string script = slurp(s.dir / "out/sweep.sbatch");
  CHECK(script.rfind("#!/bin/bash\n", 0) == 0);
  CHECK(script.find("\n#SBATCH --array=0-5\n") != std::string::npos);
  CHECK(script.find("particles job " + (s.dir / "out").string() + " \"$((0 + SLURM_ARRAY_TASK_ID))\"\n") !=
        std::string::npos);
  CHECK(fs::is_directory(s.dir / "out/logs"));
}

TEST_CASE("sweep: a scaled parameter multiplies the scenario's own value") {
  Scratch s;
  s.write("cloth.yaml",
          "scenarios: [" + kSource + "/scenarios/cloth.yaml]\ncommand: run\n"
          "parameters:\n  - {key: 'grids[0].springs.structural.ks', scale: true, values: [0.5, 4], name: k scale}\n");
  const auto r = s.run("sweep cloth.yaml -o out --emit parallel");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto jobs = table(s.dir / "out/jobs.csv");
  REQUIRE(jobs.size() == 2);
  CHECK(jobs[0].at("k scale") == "0.5");
  CHECK(jobs[0].at("command").find("--set 'grids[0].springs.structural.ks=[12.5, 0.5]'") != std::string::npos);
  CHECK(jobs[1].at("command").find("--set 'grids[0].springs.structural.ks=[100, 4]'") != std::string::npos);
}

TEST_CASE("sweep: planned from one folder with a relative sweep path, the jobs run from any other") {
  Scratch s, elsewhere;
  fs::create_directories(s.dir / "sweeps");
  fs::create_directories(s.dir / "deep/scenes");
  s.write("swing.yaml", particles::test::kSwingScenario);
  s.write("deep/swing.yaml", particles::test::kSwingScenario);
  // `..` after a link leads from the link's target: scenes/../swing.yaml is deep/swing.yaml, which
  // the sweep checks and the job must read, not the swing.yaml beside the link.
  fs::create_directory_symlink(s.dir / "deep/scenes", s.dir / "scenes");
  s.write("sweeps/swing.yaml",
          "scenarios: [../swing.yaml, ./../scenes/../swing.yaml]\ncommand: run\n"
          "parameters:\n  - {key: dt, values: [0.01, 0.02]}\n");
  const auto r = s.run("sweep sweeps/swing.yaml -o out --emit parallel");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto jobs = table(s.dir / "out/jobs.csv");
  REQUIRE(jobs.size() == 4);
  // The scenario column keeps the sweep file's spelling (the results' legends); the command line
  // names the file by its absolute path, normal where that is the same file.
  CHECK(jobs[0].at("scenario") == "../swing.yaml");
  CHECK(jobs[2].at("scenario") == "./../scenes/../swing.yaml");
  CHECK_MESSAGE(jobs[0].at("command").find(" run " + (s.dir / "swing.yaml").string() + " ") != std::string::npos,
                jobs[0].at("command"));
  CHECK_MESSAGE(jobs[2].at("command").find(" run " + fs::canonical(s.dir / "deep/swing.yaml").string() + " ") !=
                    std::string::npos,
                jobs[2].at("command"));
  for (const int index : {0, 3}) {
    CAPTURE(index);
    const auto job = elsewhere.run("job " + (s.dir / "out").string() + " " + std::to_string(index));
    CHECK_MESSAGE(job.code == 0, job.err);
    CHECK(fs::exists(s.dir / "out/jobs" / jobDir(index) / "stats.csv"));
  }
}

TEST_CASE("sweep: a bad sweep file is refused with its file, line and key before any job runs") {
  const std::string head = "scenarios: [" + kSource + "/scenarios/springs.yaml]\ncommand: run\n";
  struct Case {
    const char* what;
    std::string text;
    std::string where;    // file:line:column
    std::string message;  // part of the message
  };
  const std::vector<Case> cases = {
      {"unknown key", head + "parameter:\n  - {key: dt, values: [0.01]}\n", "bad.yaml:3:1", "did you mean 'parameters'"},
      {"unknown parameter key", head + "parameters:\n  - {key: dt, valuez: [0.01]}\n", "bad.yaml:4:15",
       "unknown key 'valuez'"},
      {"empty list", head + "parameters:\n  - {key: dt, values: []}\n", "bad.yaml:4:23", "an empty list"},
      {"empty scenarios", "scenarios: []\ncommand: run\n", "bad.yaml:1:12", "an empty list"},
      {"a --set path that does not exist", head + "parameters:\n  - {key: 'forces[1].kss', values: [1]}\n",
       "bad.yaml:4:37", "unknown key 'kss'"},
      {"a list index out of range", head + "parameters:\n  - {key: 'forces[9].ks', values: [1]}\n",
       "bad.yaml:4:36", "out of range"},
      {"a value the scenario refuses", head + "parameters:\n  - {key: 'forces[1].ks', values: [1, -2]}\n",
       "bad.yaml:4:39", "expected a number ≥ 0"},
      {"too many jobs",
       head + "parameters:\n  - {key: 'forces[1].ks', range: {from: 1, to: 100, count: 400}}\n"
              "  - {key: 'forces[2].ks', range: {from: 1, to: 100, count: 400}}\n",
       "bad.yaml:4:3", "more than 100000 jobs"},
      {"unknown integrator", head + "parameters:\n  - {key: integrator, values: [rk5]}\n", "bad.yaml:4:32",
       "unknown integrator 'rk5'"},
      {"zip of unlike lengths",
       head + "parameters:\n  - zip:\n    - {key: dt, values: [0.01, 0.02]}\n    - {key: integrator, values: [rk4]}\n",
       "bad.yaml:6:7", "lists of one length"},
      {"an option the command does not have", head + "options: {max-dtt: 3}\n", "bad.yaml:3:11", "--max-dtt"},
      {"an option value the command refuses",
       "scenarios: [" + kSource + "/scenarios/springs.yaml]\ncommand: render\noptions: {msaa: 3}\n", "bad.yaml:3:11",
       "--msaa"},
      {"an output the sweep sets", head + "options: {stats: x.csv}\n", "bad.yaml:3:11", "set by the sweep"},
      {"unknown command", "scenarios: [x.yaml]\ncommand: runn\n", "bad.yaml:2:10", "expected run, render or stability"},
      {"a missing scenario", "scenarios: [missing.yaml]\ncommand: run\n", "bad.yaml:1:13", "missing.yaml"},
      {"varied twice", head + "options: {dt: 0.01}\nparameters:\n  - {key: simulation.dt, values: [0.01]}\n",
       "bad.yaml:5:5", "varied here and also given in options"},
      {"split of a run", head + "split: 2\n", "bad.yaml:3:8", "only a render can be split"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    Scratch s;
    s.write("bad.yaml", c.text);
    const auto r = s.run("sweep bad.yaml -o out");
    CHECK(r.code == 2);
    CHECK_MESSAGE(r.err.find(c.where + ": error: ") != std::string::npos, r.err);
    CHECK_MESSAGE(r.err.find(c.message) != std::string::npos, r.err);
    CHECK_FALSE(fs::exists(s.dir / "out"));  // nothing ran, nothing was written
  }
}

TEST_CASE("sweep: values that load alone but not together in one job are refused at the value") {
  Scratch s;
  // The cloth's mouse drags from 1.5 s to 3.5 s: from 3 and to 2 each load, but not in one job.
  s.write("bad.yaml", "scenarios: [" + kSource +
                          "/scenarios/cloth.yaml]\ncommand: run\nparameters:\n"
                          "  - {key: 'mouse[0].from', values: [1, 3]}\n"
                          "  - {key: 'mouse[0].to', values: [2, 3.5]}\n");
  const auto r = s.run("sweep bad.yaml -o out");
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.find("bad.yaml:5:35: error: parameters[1].values[0]: ") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("mouse[0].to (from the sweep's mouse[0].to=2): expected a time after 'from' (3 s), got 2 "
                           "(with mouse[0].from=3, mouse[0].to=2)") != std::string::npos,
                r.err);
  CHECK_FALSE(fs::exists(s.dir / "out"));
}

namespace {

// A scene of n² particles and 2n(n − 1) springs written out one entry each (n = 55: 3,025 and
// 5,940 in 0.5 MB of YAML, bench/sweep_planning.sh's "explicit"): loading it takes 0.4 s, mostly parsing.
std::string explicitCloth(int n) {
  std::string text = "name: explicit_cloth\nsimulation: {integrator: rk4, dt: 0.01, duration: 1}\nparticles:\n";
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      text += "  - {name: p" + std::to_string(r) + "_" + std::to_string(c) + ", pos: [" + std::to_string(c * 0.08) +
              ", " + std::to_string(-r * 0.08) + "], mass: 0.002" + (r == 0 ? ", fixed: true}\n" : "}\n");
    }
  }
  text += "forces:\n  - {type: gravity}\n  - {type: drag, kd: 0.002}\n";
  auto spring = [&](int r, int c, int r2, int c2) {
    text += "  - {type: spring, a: p" + std::to_string(r) + "_" + std::to_string(c) + ", b: p" + std::to_string(r2) +
            "_" + std::to_string(c2) + ", ks: 25, kd: 0.01}\n";
  };
  for (int r = 0; r < n; ++r) {
    for (int c = 0; c < n; ++c) {
      if (c + 1 < n) spring(r, c, r, c + 1);
      if (r + 1 < n) spring(r, c, r + 1, c);
    }
  }
  return text;
}

}  // namespace

TEST_CASE("sweep: a thousand values over a scenario of 3,025 particles plan without loading it per value") {
  Scratch s;
  s.write("explicit.yaml", explicitCloth(55));
  s.write("many.yaml",
          "scenarios: [explicit.yaml]\ncommand: run\nparameters:\n"
          "  - {key: 'forces[2].ks', range: {from: 1, to: 100, count: 1000}}\n");
  const auto start = std::chrono::steady_clock::now();
  const auto r = s.run("sweep many.yaml -o out --emit parallel");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK_MESSAGE(r.err.empty(), r.err);  // no progress where stderr is not a terminal
  const auto jobs = table(s.dir / "out/jobs.csv");
  REQUIRE(jobs.size() == 1000);
  CHECK(jobs[0].at("forces[2].ks") == "1");
  CHECK(jobs[999].at("forces[2].ks") == "100");
  CHECK(jobs[999].at("command").find("--set 'forces[2].ks=100'") != std::string::npos);
  // A guard, not a benchmark (bench/README.md, "Planning a sweep": about a second): loading the
  // scene for each value took 407 s.
  CHECK_MESSAGE(seconds < 60, seconds << " s");
}

TEST_CASE("sweep --jobs 2: every job runs, a failure is listed with its message and exit 1, results gathered") {
  Scratch s;
  // dt 0.05 with Euler makes the stiff spring blow up; the other jobs still run.
  s.write("mixed.yaml", "scenarios: [" + kSource + "/scenarios/springs.yaml]\ncommand: run\n"
                        "options: {duration: 2, integrator: euler}\n"
                        "parameters:\n  - {key: dt, values: [0.001, 0.002, 0.05]}\n");
  const auto r = s.run("sweep mixed.yaml -o out --jobs 2");
  CHECK(r.code == 1);
  CHECK_MESSAGE(r.err.find("1 job failed:") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("job 2 (") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("dt = 0.05") != std::string::npos, r.err);
  CHECK_MESSAGE(r.err.find("exit 1") != std::string::npos, r.err);
  CHECK_MESSAGE(r.out.find("3 ran (2 ok, 1 failed), 0 done before") != std::string::npos, r.out);
  const auto results = table(s.dir / "out/results.csv");
  REQUIRE(results.size() == 3);
  CHECK(results[0].at("status") == "ok");
  CHECK(results[1].at("status") == "ok");
  CHECK(results[2].at("status") == "failed");
  CHECK(results[2].at("exit") == "1");
  CHECK(results[2].at("message").find("smaller") != std::string::npos);  // the explosion's advice
  // Headline numbers: the energy of the finer step is nearer the start's (a damped system loses it).
  const double e0 = std::stod(results[0].at("initial_energy"));
  const double e1 = std::stod(results[0].at("final_energy")), e2 = std::stod(results[1].at("final_energy"));
  CHECK(e1 < e0);
  CHECK(std::abs(e1 - e2) < 0.1 * std::abs(e0));
  CHECK(results[0].at("worst_constraint_error") == "0");
  CHECK(std::stod(results[0].at("wall_seconds")) > 0);
  // One parameter varies: the figure is drawn.
  CHECK(fs::file_size(s.dir / "out/results.svg") > 1000);

  // gather alone writes the same table.
  const std::string before = slurp(s.dir / "out/results.csv");
  const auto g = s.run("gather out -o again.csv --plot none");
  REQUIRE_MESSAGE(g.code == 0, g.err);
  CHECK(slurp(s.dir / "again.csv") == before);
  CHECK(s.run("gather nowhere").code == 2);
}

TEST_CASE("sweep: a killed sweep resumes, and no finished job runs again") {
  Scratch s;
  // Eight cloth runs of about a tenth of a second each, one at a time.
  s.write("resume.yaml", "scenarios: [" + kSource + "/scenarios/cloth.yaml]\ncommand: run\n"
                         "options: {duration: 1.5}\n"
                         "parameters:\n  - {key: 'forces[1].kd', range: {from: 0.001, to: 0.008, count: 8}}\n");
  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(s.dir.c_str()) != 0 || !std::freopen("first.txt", "w", stdout) || !std::freopen("first_err.txt", "w", stderr)) ::_exit(127);
    ::execl(exe.c_str(), "particles", "sweep", "resume.yaml", "-o", "out", "--jobs", "1", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  auto records = [&] {
    size_t n = 0;
    for (int i = 0; i < 8; ++i) n += fs::exists(s.dir / "out/jobs" / jobDir(i) / "record.txt");
    return n;
  };
  const auto start = std::chrono::steady_clock::now();
  while (records() < 3 && std::chrono::steady_clock::now() - start < std::chrono::seconds(120)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ::kill(pid, SIGKILL);  // no chance to tidy up: its running job is stopped by the kernel's parent-death signal
  int status = 0;
  ::waitpid(pid, &status, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // the orphaned job ends (or finishes)
  struct Seen {
    ino_t inode;
    timespec mtime;
  };
  std::map<int, Seen> finished;
  for (int i = 0; i < 8; ++i) {
    struct stat st {};
    if (::stat((s.dir / "out/jobs" / jobDir(i) / "record.txt").c_str(), &st) == 0) finished[i] = {st.st_ino, st.st_mtim};
  }
  REQUIRE(finished.size() >= 3);
  REQUIRE(finished.size() < 8);  // killed midway

  const auto r = s.run("sweep resume.yaml -o out --jobs 1");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const std::string ran = std::to_string(8 - finished.size());
  const std::string summary = ran + " ran (" + ran + " ok, 0 failed), " + std::to_string(finished.size()) + " done before";
  CHECK_MESSAGE(r.out.find(summary) != std::string::npos, r.out);
  for (const auto& [i, seen] : finished) {
    CAPTURE(i);
    struct stat st {};
    REQUIRE(::stat((s.dir / "out/jobs" / jobDir(i) / "record.txt").c_str(), &st) == 0);
    CHECK(st.st_ino == seen.inode);  // the record was not written again: the job did not run
    CHECK(st.st_mtim.tv_sec == seen.mtime.tv_sec);
    CHECK(st.st_mtim.tv_nsec == seen.mtime.tv_nsec);
  }
  const auto results = table(s.dir / "out/results.csv");
  REQUIRE(results.size() == 8);
  for (const auto& row : results) CHECK(row.at("status") == "ok");

  // --force runs them all again.
  const auto forced = s.run("sweep resume.yaml -o out --jobs 2 --force");
  REQUIRE_MESSAGE(forced.code == 0, forced.err);
  CHECK_MESSAGE(forced.out.find("8 ran (8 ok, 0 failed), 0 done before") != std::string::npos, forced.out);
}

// The sweep's handler (src/app/stop_signal.hpp, StopMode::interruptWaits) must interrupt its wait
// for a job: with system calls restarted after it, the sweep would wait for the running job to end.
TEST_CASE("sweep: SIGINT and SIGTERM stop the running job at once and exit 128 + the signal") {
  for (const int signal : {SIGINT, SIGTERM}) {
    CAPTURE(signal);
    Scratch s;
    // Cloth runs of about 40 s each (0.1 s per 1.5 simulated s), one at a time: none ends by itself.
    s.write("long.yaml", "scenarios: [" + kSource +
                             "/scenarios/cloth.yaml]\ncommand: run\n"
                             "options: {duration: 600}\n"
                             "parameters:\n  - {key: 'forces[1].kd', range: {from: 0.001, to: 0.002, count: 2}}\n");
    const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
      if (::chdir(s.dir.c_str()) != 0 || !std::freopen("err.txt", "w", stderr)) ::_exit(127);
      ::execl(exe.c_str(), "particles", "sweep", "long.yaml", "-o", "out", "--jobs", "1", "--quiet",
              static_cast<char*>(nullptr));
      ::_exit(127);
    }
    // The first job has started once its log exists (the sweep opens it before it runs the job).
    const auto start = std::chrono::steady_clock::now();
    while (!fs::exists(s.dir / "out/jobs" / jobDir(0) / "log.txt") &&
           std::chrono::steady_clock::now() - start < std::chrono::seconds(60)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // the sweep is now waiting for it
    ::kill(pid, signal);
    const auto signalled = std::chrono::steady_clock::now();
    int status = 0;
    pid_t waited = 0;
    while ((waited = ::waitpid(pid, &status, WNOHANG)) == 0 &&
           std::chrono::steady_clock::now() - signalled < std::chrono::seconds(30)) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    if (waited == 0) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &status, 0);
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    REQUIRE_MESSAGE(waited == pid, "the sweep still ran 30 s after the signal");
    CHECK(seconds < 10);  // far less than the job's 40 s
    CHECK(WIFEXITED(status));
    CHECK(WEXITSTATUS(status) == 128 + signal);
    const std::string err = slurp(s.dir / "err.txt");
    CHECK_MESSAGE(
        err.find("long.yaml: interrupted after 0 of 2 jobs; run the same command again to resume") != std::string::npos,
        err);
    CHECK_FALSE(fs::exists(s.dir / "out/jobs" / jobDir(0) / "record.txt"));  // stopped, not finished
  }
}

TEST_CASE("sweep: a render split into segments, joined by concat into one video") {
  Scratch s;
  s.write("swing.yaml", particles::test::kSwingScenario);
  s.write("split.yaml", "scenarios: [swing.yaml]\ncommand: render\noptions: {msaa: 1}\nsplit: 2\n"
                        "parameters:\n  - {key: dt, values: [0.01, 0.005]}\n");
  const auto r = s.run("sweep split.yaml -o out --jobs 2");
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const auto results = table(s.dir / "out/results.csv");
  REQUIRE(results.size() == 6);  // 2 × 2 segments, then 2 joins
  for (int i = 0; i < 4; ++i) {
    CHECK(results[size_t(i)].at("stage") == "segment");
    CHECK(results[size_t(i)].at("frames") == "5");  // 10 frames in two halves
  }
  for (int i = 4; i < 6; ++i) {
    CAPTURE(i);
    CHECK(results[size_t(i)].at("stage") == "concat");
    CHECK(results[size_t(i)].at("status") == "ok");
    const auto info = particles::test::probeVideo(s.dir / "out/jobs" / jobDir(i) / "video.mp4");
    CHECK(info.codec == "h264");
    CHECK(info.frames == 10);
    CHECK(info.fps == doctest::Approx(10));
  }
  const std::string joined = slurp(s.dir / "out/jobs.csv");
  CHECK(joined.find("concat " + (s.dir / "out/jobs/000000/segment.mp4").string() + " " +
                    (s.dir / "out/jobs/000001/segment.mp4").string()) != std::string::npos);
}

TEST_CASE("job record: done by this very binary counts, by another build, or with a lost output, it runs again") {
  Scratch s;
  const std::string job = "run " + kSource + "/scenarios/springs.yaml --duration 0.2 --stats s.csv --record r.txt";
  auto r = s.run(job);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  // The record names the binary by its build ID (16 hex digits), beside the release number.
  std::string text = slurp(s.dir / "r.txt");
  const auto at = text.find("version: 0.");
  REQUIRE(at != std::string::npos);
  const std::string versionLine = text.substr(at, text.find('\n', at) - at);
  const auto build = versionLine.find(" build ");
  REQUIRE_MESSAGE(build != std::string::npos, versionLine);
  const std::string id = versionLine.substr(build + 7);
  CHECK(id.size() == 16);
  CHECK(id.find_first_not_of("0123456789abcdef") == std::string::npos);
  CHECK(s.run("--version").out.find(versionLine.substr(9)) != std::string::npos);

  r = s.run(job);
  CHECK(r.code == 0);
  CHECK_MESSAGE(r.err.find("done before") != std::string::npos, r.err);

  // The same record written by another build: the job runs again and records this one.
  const std::string other = "0.1.0 build 0123456789abcdef";
  s.write("r.txt", text.replace(at + 9, versionLine.size() - 9, other));
  r = s.run(job);
  CHECK(r.code == 0);
  CHECK_MESSAGE(r.err.find("done before") == std::string::npos, r.err);
  CHECK(slurp(s.dir / "r.txt").find(other) == std::string::npos);

  // An output gone: it runs again.
  fs::remove(s.dir / "s.csv");
  r = s.run(job);
  CHECK(r.err.find("done before") == std::string::npos);
  CHECK(fs::exists(s.dir / "s.csv"));
}

namespace {

// Runs `argv` (argv[0] a path) in `dir` with no shell between, its environment this process's
// without the names in `unset` and with `set` (NAME=VALUE) added; stdout and stderr into files
// there. Waits for that one process.
particles::test::Result runDirect(const fs::path& dir, const std::vector<std::string>& argv,
                                  const std::vector<std::string>& set = {},
                                  const std::vector<std::string>& unset = {}) {
  std::vector<std::string> environment;
  for (char** e = environ; *e != nullptr; ++e) {
    const std::string entry = *e;
    const std::string name = entry.substr(0, entry.find('='));
    const auto named = [&](const std::string& s) { return s == name || s.rfind(name + "=", 0) == 0; };
    if (std::none_of(unset.begin(), unset.end(), named) && std::none_of(set.begin(), set.end(), named)) {
      environment.push_back(entry);
    }
  }
  environment.insert(environment.end(), set.begin(), set.end());
  std::vector<std::string> args = argv;
  std::vector<char*> argvPointers, environmentPointers;
  for (std::string& a : args) argvPointers.push_back(a.data());
  argvPointers.push_back(nullptr);
  for (std::string& e : environment) environmentPointers.push_back(e.data());
  environmentPointers.push_back(nullptr);
  const std::string out = (dir / "direct_out.txt").string(), err = (dir / "direct_err.txt").string();
  // The child's freopen would flush what this process still buffers into its own output.
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0 || !std::freopen(out.c_str(), "w", stdout) ||
        !std::freopen(err.c_str(), "w", stderr)) {
      ::_exit(127);
    }
    ::execve(argvPointers[0], argvPointers.data(), environmentPointers.data());
    ::_exit(127);
  }
  int status = 0;
  REQUIRE(::waitpid(pid, &status, 0) == pid);
  particles::test::Result r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// A stand-in for the program a sweep runs (--program): it appends its arguments to OUT/starts.txt,
// one line per job in the order the jobs start, then runs the real program (a link beside it) with
// them. Fixed text: it names no path.
void writeLoggingProgram(const Scratch& s) {
  const fs::path script = s.write("logging-particles",
                                  "#!/bin/sh\n"
                                  "printf '%s\\n' \"$*\" >> \"$2/starts.txt\"\n"
                                  "exec \"${0%/*}/real-particles\" \"$@\"\n");
  fs::permissions(script, fs::perms::owner_exec, fs::perm_options::add);
  fs::create_symlink(fs::read_symlink("/proc/self/exe").parent_path() / "particles", s.dir / "real-particles");
}

// The jobs' start lines, `job OUT INDEX [--force] [--threads N]`, as (index, threads), threads 0
// when not given.
std::vector<std::pair<int, int>> starts(const fs::path& out) {
  std::vector<std::pair<int, int>> seen;
  for (const std::string& line : lines(slurp(out / "starts.txt"))) {
    std::istringstream words(line);
    std::string job, folder, word;
    int index = -1, threads = 0;
    words >> job >> folder >> index;
    while (words >> word) {
      if (word == "--threads") words >> threads;
    }
    seen.emplace_back(index, threads);
  }
  return seen;
}

// What two runs of the same jobs must agree on: each record without its time (seconds, and the
// wall time a run reports), and results.csv without its timing columns.
std::string withoutTimings(const fs::path& out, size_t jobs) {
  std::string text;
  for (size_t i = 0; i < jobs; ++i) {
    for (const std::string& line : lines(slurp(out / "jobs" / jobDir(int(i)) / "record.txt"))) {
      if (line.rfind("seconds: ", 0) != 0 && line.rfind("value.wall_seconds: ", 0) != 0) text += line + "\n";
    }
  }
  const auto rows = lines(slurp(out / "results.csv"));
  const auto header = fields(rows.at(0));
  for (const std::string& row : rows) {
    const auto f = fields(row);
    for (size_t k = 0; k < f.size(); ++k) {
      if (header[k] != "seconds" && header[k] != "wall_seconds") text += f[k] + ",";
    }
    text += "\n";
  }
  return text;
}

// Four cloth runs whose costs differ by their steps (dt) and evaluations per step (integrator):
// estimated 1 : 10 : 1 : 2 (scaled steps × evaluations), so they start 1, 3, then 0 and 2 (a tie,
// in their own order).
const std::string kUnequalSweep = "scenarios: [" + kSource +
                                  "/scenarios/cloth.yaml]\n"
                                  "command: run\n"
                                  "options: {duration: 0.2, integrator: euler}\n"
                                  "parameters:\n"
                                  "  - {key: dt, values: [0.01, 0.001, 0.01, 0.005]}\n";

}  // namespace

TEST_CASE("sweep: the longest jobs start first, each with its share of the cores, and the records do not change") {
  Scratch s;
  writeLoggingProgram(s);
  s.write("unequal.yaml", kUnequalSweep);
  const int cores = particles::input::availableCores();
  const std::string program = (s.dir / "logging-particles").string();
  const std::string exe = (s.dir / "real-particles").string();
  const std::vector<std::string> sweep = {exe, "sweep", "unequal.yaml", "-o", "out", "--program", program, "--force"};
  auto run = [&](const std::string& jobs, const std::vector<std::string>& set) {
    fs::remove(s.dir / "out/starts.txt");
    std::vector<std::string> argv = sweep;
    argv.insert(argv.end(), {"--jobs", jobs});
    const auto r = runDirect(s.dir, argv, set, {"PARTICLES_THREADS"});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    return starts(s.dir / "out");
  };

  // One at a time: in decreasing cost, each job with every core.
  const auto one = run("1", {});
  const std::vector<std::pair<int, int>> expected = {{1, cores}, {3, cores}, {0, cores}, {2, cores}};
  CHECK(one == expected);
  const std::string reference = withoutTimings(s.dir / "out", 4);
  const std::string jobsCsv = slurp(s.dir / "out/jobs.csv");

  // Two at once: jobs 1 and 3 first, then 0 and 2 as they end. Two jobs started together log in
  // either order, but the second pair starts only after one of the first has ended, so after both
  // logged. While two or more remain to start, half the cores each (at least one); the last job
  // may get them all.
  const auto two = run("2", {});
  REQUIRE(two.size() == 4);
  using Pair = std::set<int>;
  CHECK(Pair{two[0].first, two[1].first} == Pair{1, 3});
  CHECK(Pair{two[2].first, two[3].first} == Pair{0, 2});
  for (size_t k = 0; k < two.size(); ++k) {
    CAPTURE(k);
    CHECK(two[k].second >= std::max(1, cores / 2));
    CHECK(two[k].second <= (k < 2 ? std::max(1, cores / 2) : cores));
  }
  // The same records and results, whatever the order and threads: those of a serial run too.
  CHECK(withoutTimings(s.dir / "out", 4) == reference);
  run("1", {"PARTICLES_THREADS=1"});
  CHECK(withoutTimings(s.dir / "out", 4) == reference);
  CHECK(slurp(s.dir / "out/jobs.csv") == jobsCsv);
}

TEST_CASE("sweep: an explicit thread count is respected: the sweep file's, else PARTICLES_THREADS") {
  Scratch s;
  writeLoggingProgram(s);
  s.write("unequal.yaml", kUnequalSweep);
  s.write(
      "given.yaml",
      std::string(kUnequalSweep).replace(kUnequalSweep.find("integrator: euler"), 17, "integrator: euler, threads: 3"));
  const std::string program = (s.dir / "logging-particles").string();
  const std::string exe = (s.dir / "real-particles").string();

  // The sweep file's threads: on every job's command line (jobs.csv), and the sweep adds none.
  auto r = runDirect(s.dir, {exe, "sweep", "given.yaml", "-o", "given", "--jobs", "2", "--program", program}, {},
                     {"PARTICLES_THREADS"});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK_MESSAGE(r.err.find("threads: the sweep file's") != std::string::npos, r.err);
  for (const auto& [index, threads] : starts(s.dir / "given")) CHECK(threads == 0);
  for (const auto& row : table(s.dir / "given/jobs.csv"))
    CHECK(row.at("command").find(" --threads 3 ") != std::string::npos);
  // `particles job` keeps the line's own --threads over its option, and records the line alone.
  r = runDirect(s.dir, {exe, "job", "given", "0", "--threads", "2", "--force"});
  CHECK_MESSAGE(r.code == 0, r.err);
  const auto jobs = table(s.dir / "given/jobs.csv");
  const std::string record = slurp(s.dir / "given/jobs/000000/record.txt");
  const std::string line = jobs[0].at("command");
  CHECK_MESSAGE(record.find("command: " + line.substr(line.find(" run ") + 1) + "\n") != std::string::npos, record);

  // PARTICLES_THREADS in the sweep's environment: the jobs inherit it, the sweep adds none.
  r = runDirect(s.dir, {exe, "sweep", "unequal.yaml", "-o", "inherited", "--jobs", "2", "--program", program},
                {"PARTICLES_THREADS=1"});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK_MESSAGE(r.err.find("threads: PARTICLES_THREADS") != std::string::npos, r.err);
  for (const auto& [index, threads] : starts(s.dir / "inherited")) CHECK(threads == 0);
  // ... checked before anything is written.
  r = runDirect(s.dir, {exe, "sweep", "unequal.yaml", "-o", "refused", "--program", program},
                {"PARTICLES_THREADS=many"});
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.find("PARTICLES_THREADS") != std::string::npos, r.err);
  CHECK_FALSE(fs::exists(s.dir / "refused"));
}

TEST_CASE("sweep: a Slurm task runs its job on the CPUs Slurm gives it, as one checked argument") {
  Scratch s;
  writeLoggingProgram(s);
  s.write("unequal.yaml", kUnequalSweep);
  const std::string exe = (s.dir / "real-particles").string();
  auto r = runDirect(s.dir, {exe, "sweep", "unequal.yaml", "-o", "array", "--emit", "slurm", "--program",
                             (s.dir / "logging-particles").string()});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  const std::string script = (s.dir / "array/sweep.sbatch").string();
  struct Task {
    particles::test::Result result;
    std::vector<std::pair<int, int>> started;
  };
  auto task = [&](const std::vector<std::string>& set) {
    fs::remove(s.dir / "array/starts.txt");
    Task t;
    t.result = runDirect(s.dir, {"/bin/bash", script}, set, {"PARTICLES_THREADS", "SLURM_CPUS_PER_TASK"});
    t.started = starts(s.dir / "array");
    return t;
  };
  using Started = std::vector<std::pair<int, int>>;
  // --cpus-per-task=2: the job's --threads.
  const Task withCpus = task({"SLURM_ARRAY_TASK_ID=1", "SLURM_CPUS_PER_TASK=2"});
  CHECK_MESSAGE(withCpus.result.code == 0, withCpus.result.err);
  CHECK(withCpus.started == Started{{1, 2}});
  // No CPUs asked for: the job's default (the CPUs the task is bound to).
  CHECK(task({"SLURM_ARRAY_TASK_ID=2"}).started == Started{{2, 0}});
  // PARTICLES_THREADS set: that.
  CHECK(task({"SLURM_ARRAY_TASK_ID=2", "SLURM_CPUS_PER_TASK=2", "PARTICLES_THREADS=1"}).started == Started{{2, 0}});
  // Slurm's value is data: shell text in it is one argument, refused as a thread count.
  const Task hostile = task({"SLURM_ARRAY_TASK_ID=0", "SLURM_CPUS_PER_TASK=2; touch PWNED"});
  CHECK(hostile.result.code == 2);
  CHECK_MESSAGE(hostile.result.err.find("--threads") != std::string::npos, hostile.result.err);
  CHECK_FALSE(fs::exists(s.dir / "PWNED"));
  CHECK_FALSE(fs::exists(s.dir / "array/PWNED"));
}
