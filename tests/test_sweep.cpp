// `particles sweep` and `particles gather` (docs/sweeps.md), through the real program: a sweep file
// expanded into jobs, bad sweep files refused before any job runs, jobs run here with failures
// listed, a killed sweep resumed without running a finished job again, and a render split into
// segments and joined. GNU parallel and Slurm run the emitted lists in tests/sweep/ (CTest);
// hostile sweep files and tampered sweep folders are test_sweep_hostile.cpp's.
#include <doctest/doctest.h>
#include <sys/stat.h>

#include <array>
#include <cstdio>
#include <map>

#include "cli_support.hpp"
#include "support/video_probe.hpp"

namespace {

using particles::test::lines;
using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;

const std::string kSource = PARTICLES_SOURCE_DIR;

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
