// Through the real program: an output is never one of the command's inputs nor another of its
// outputs (src/output/distinct_files.hpp), refused with exit 2 before any work and with every
// file left as it was; options whose outputs cannot be written (a figure's extension, a --record
// folder, --diff not a PNG) refused up front; outputs at a FIFO that no process reads refused at
// once instead of hanging in open(); and SIGTERM ending a render whose writes block. Every run is
// guarded (Scratch::runBounded: killed after 60 s) so that a hang fails the test instead of CI.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "cli_support.hpp"

using namespace particles::test;
namespace fs = std::filesystem;

namespace {

// Every file of the folder (recursively) with its bytes, to check that a refused command touched
// nothing.
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string name = fs::relative(e.path(), dir).string();
    files[name] = e.is_symlink()        ? "-> " + fs::read_symlink(e.path()).string()
                  : e.is_regular_file() ? slurp(e.path())
                                        : std::string("(not a file)");
  }
  return files;
}

struct Refusal {
  std::string args;
  std::string err;  // all of stderr
};

// Each command exits 2 with its message, leaving the folder byte for byte as it was.
void checkRefused(const Scratch& s, const std::vector<Refusal>& refusals) {
  const auto before = snapshot(s.dir);
  for (const Refusal& r : refusals) {
    CAPTURE(r.args);
    Scratch::Usage usage;
    const Result result = s.runBounded(r.args, usage);
    CHECK(result.code == 2);
    CHECK(result.err == r.err);
    CHECK(snapshot(s.dir) == before);
  }
}

struct stat lstatOf(const fs::path& path) {
  struct stat st {};
  REQUIRE_MESSAGE(::lstat(path.c_str(), &st) == 0, path << ": " << std::strerror(errno));
  return st;
}

std::string sameFile(const std::string& a, const std::string& b, const char* what) {
  return "error: " + a + "' and " + b + "' name the same file; an output never replaces " + what + "\n";
}

}  // namespace

TEST_CASE("a --record file is never another output or the scenario") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  s.write("x.csv", "a previous run's stats\n");
  s.write("f.png", "a previous frame\n");
  s.write("x.svg", "a previous figure\n");
  REQUIRE(s.run("render s.yaml -o a0.mp4 --frames 0:5 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o a1.mp4 --frames 5: --quiet").code == 0);
  checkRefused(
      s, {
             {"run s.yaml --quiet --stats x.csv --record x.csv",
              sameFile("--stats 'x.csv", "--record 'x.csv", "another output")},
             {"run s.yaml --quiet --trace x.csv --record ./x.csv",
              sameFile("--trace 'x.csv", "--record './x.csv", "another output")},
             {"run s.yaml --quiet --record s.yaml", sameFile("--record 's.yaml", "the scenario 's.yaml", "an input")},
             {"render s.yaml --quiet -o f.png --at 0.5 --record f.png",
              sameFile("-o 'f.png", "--record 'f.png", "another output")},
             {"stability s.yaml --quiet --integrators euler --max-dt 0.02 --csv x.csv --record x.csv",
              sameFile("--csv 'x.csv", "--record 'x.csv", "another output")},
             {"stability s.yaml --quiet --integrators euler --max-dt 0.02 --plot x.svg --record x.svg",
              sameFile("--plot 'x.svg", "--record 'x.svg", "another output")},
             {"concat a0.mp4 a1.mp4 -o j.mp4 --record a0.mp4",
              sameFile("--record 'a0.mp4", "the segment 'a0.mp4", "an input")},
             // The check this replaces compared --stats and --trace as text.
             {"run s.yaml --quiet --stats x.csv --trace ./x.csv",
              sameFile("--stats 'x.csv", "--trace './x.csv", "another output")},
         });
}

TEST_CASE("concat -o never names a segment, by its name, through .. or a link") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o a0.mp4 --frames 0:5 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o a1.mp4 --frames 5: --quiet").code == 0);
  fs::create_directory(s.dir / "d");
  fs::create_symlink("a0.mp4", s.dir / "link.mp4");
  checkRefused(
      s, {
             {"concat a0.mp4 a1.mp4 -o a0.mp4 --quiet", sameFile("-o 'a0.mp4", "the segment 'a0.mp4", "an input")},
             {"concat a0.mp4 a1.mp4 -o ./d/../a1.mp4 --quiet",
              sameFile("-o './d/../a1.mp4", "the segment 'a1.mp4", "an input")},
             {"concat a0.mp4 a1.mp4 -o link.mp4 --quiet", sameFile("-o 'link.mp4", "the segment 'a0.mp4", "an input")},
         });
  // Joining a segment to itself reads it twice and writes elsewhere: allowed.
  const Result twice = s.run("concat a0.mp4 a0.mp4 -o j.mp4 --quiet");
  CHECK_MESSAGE(twice.code == 0, twice.err);
}

TEST_CASE("compare --diff never replaces the frames it compares") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o a.png --at 0.2 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o b.png --at 0.3 --quiet").code == 0);
  fs::create_symlink("b.png", s.dir / "link.png");
  checkRefused(
      s,
      {
          {"compare a.png b.png --diff a.png", sameFile("--diff 'a.png", "the expected frame 'a.png", "an input")},
          {"compare a.png b.png --diff link.png", sameFile("--diff 'link.png", "the actual frame 'b.png", "an input")},
      });
}

TEST_CASE("gather's outputs are never its job table, a record or each other, plot's never its CSV") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  s.write("sweep.yaml",
          "scenarios: [s.yaml]\ncommand: run\noptions: {duration: 0.2}\n"
          "parameters:\n  - {key: dt, values: [0.01, 0.02]}\n");
  REQUIRE(s.run("sweep sweep.yaml -o out --emit parallel --quiet").code == 0);
  const std::string dir0 = fs::path("out/jobs/000000").string(), dir1 = fs::path("out/jobs/000001").string();
  REQUIRE(fs::is_directory(s.dir / dir1));
  s.write(dir1 + "/record.txt", "# particles job record\nversion: x\nexit: 3\n");
  REQUIRE(s.run("run s.yaml --quiet --duration 0.2 --stats s.svg").code == 0);  // a stats CSV named .svg
  checkRefused(
      s, {
             {"gather out -o out/jobs.csv --quiet",
              sameFile("-o 'out/jobs.csv", "the job table 'out/jobs.csv", "an input")},
             {"gather out -o r.png --plot r.png --quiet", sameFile("-o 'r.png", "--plot 'r.png", "another output")},
             {"gather out -o " + dir1 + "/record.txt --quiet",
              sameFile("-o '" + dir1 + "/record.txt", "the record '" + dir1 + "/record.txt", "an input")},
             // A record not written yet, by the name its job will write it under.
             {"gather out -o out/jobs/../" + dir0.substr(4) + "/record.txt --quiet",
              sameFile("-o 'out/jobs/../" + dir0.substr(4) + "/record.txt", "the record '" + dir0 + "/record.txt",
                       "an input")},
             {"plot s.svg -o s.svg --quiet", sameFile("-o 's.svg", "the CSV 's.svg", "an input")},
         });
}

// What golden and sweep write, by their rows of the command table (src/app/command_table.cpp): a
// golden report folder is replaced whole, so nothing it reads may lie in it; a sweep never writes
// over its sweep file or a scenario. The default folders and what a manifest or sweep file names are
// checked, by the same rule, once the file is read.
std::string inFolder(const std::string& folder, const std::string& input) {
  return "error: -o '" + folder + "' is a folder replaced whole, and " + input +
         "' is in it; an output never replaces an input\n";
}

TEST_CASE("golden's report folder never holds what it reads, a sweep never writes over its inputs") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  s.write("m.yaml", "references: report/refs\nstates:\n  - {scenario: s.yaml, times: [0.1]}\n");
  fs::create_directories(s.dir / "shards/rep");
  fs::create_directories(s.dir / "out");
  fs::create_directories(s.dir / "sweep-jobs");
  const std::string sweep = "scenarios: [s.yaml]\ncommand: run\nparameters:\n  - {key: dt, values: [0.01]}\n";
  s.write("out/jobs.csv", sweep);
  s.write("sweep-jobs/jobs.csv", sweep);
  s.write("out/results.csv", kSwingScenario);
  s.write("onto-results.yaml",
          "scenarios: [out/results.csv]\ncommand: run\nparameters:\n  - {key: dt, values: [0.01]}\n");
  checkRefused(s,
               {
                   {"golden check m.yaml -o . -q", inFolder(".", "the manifest 'm.yaml")},
                   // The references' folder the manifest names, not there yet.
                   {"golden check m.yaml -o report -q", inFolder("report", "the references './report/refs")},
                   {"golden report shards/rep -o shards -q", inFolder("shards", "the report folder 'shards/rep")},
                   {"golden report shards/rep -o shards/rep -q",
                    sameFile("-o 'shards/rep", "the report folder 'shards/rep", "an input")},
                   {"sweep out/jobs.csv -o out --quiet",
                    sameFile("the job table 'out/jobs.csv", "the sweep file 'out/jobs.csv", "an input")},
                   // The default folder, sweep-NAME, named after the sweep file: jobs.
                   {"sweep sweep-jobs/jobs.csv --quiet",
                    sameFile("the job table 'sweep-jobs/jobs.csv", "the sweep file 'sweep-jobs/jobs.csv", "an input")},
                   {"sweep onto-results.yaml -o out --emit parallel --quiet",
                    sameFile("the results 'out/results.csv", "the scenario 'out/results.csv", "an input")},
               });
}

TEST_CASE("a figure's extension, a --record folder and --diff's format are refused before any work") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("run s.yaml --quiet --duration 0.2 --stats good.csv").code == 0);
  REQUIRE(s.run("render s.yaml -o a.png --at 0.2 --quiet").code == 0);
  s.write("sweep.yaml",
          "scenarios: [s.yaml]\ncommand: run\noptions: {duration: 0.2}\n"
          "parameters:\n  - {key: dt, values: [0.01, 0.02]}\n");
  REQUIRE(s.run("sweep sweep.yaml -o out --emit parallel --quiet").code == 0);
  fs::create_directory(s.dir / "folder");
  checkRefused(
      s, {
             {"plot good.csv -o x.txt --quiet", "error: -o x.txt: a figure is .svg, .png or .pdf, not '.txt'\n"},
             {"gather out --plot x.txt --quiet", "error: --plot x.txt: a figure is .svg, .png or .pdf, not '.txt'\n"},
             // Before the study runs and its --csv is written.
             {"stability s.yaml --quiet --integrators euler --csv dt.csv --plot x.txt",
              "error: --plot x.txt: a figure is .svg, .png or .pdf, not '.txt'\n"},
             // Before the run, so that no --stats is left behind.
             {"run s.yaml --quiet --stats st.csv --record folder",
              "error: --record folder: a directory; a record is a regular file\n"},
             {"run s.yaml --quiet --stats st.csv --record missing/record.txt",
              "error: --record missing/record.txt: no folder missing\n"},
             {"render s.yaml --quiet -o x.mp4 --record missing/record.txt",
              "error: --record missing/record.txt: no folder missing\n"},
             {"compare a.png a.png --diff x.svg",
              "error: --diff x.svg: the picture of the differences is a PNG; name it .png\n"},
         });
}

TEST_CASE("an output at a FIFO nobody reads is refused at once, and stays a FIFO") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("run s.yaml --quiet --duration 0.2 --stats good.csv").code == 0);
  s.write("sweep.yaml",
          "scenarios: [s.yaml]\ncommand: run\noptions: {duration: 0.2}\n"
          "parameters:\n  - {key: dt, values: [0.01, 0.02]}\n");
  fs::create_directory(s.dir / "out");
  for (const char* fifo : {"k.mp4", "k.csv", "k.svg", "out/jobs.csv", "record.txt"}) {
    REQUIRE(::mkfifo((s.dir / fifo).c_str(), 0600) == 0);
  }
  struct Case {
    std::string args;
    int code;
    std::string err;
  };
  const Case cases[] = {
      {"render s.yaml -o k.mp4 --quiet", 3, "error: cannot write k.mp4: it is a FIFO and no process is reading it\n"},
      {"run s.yaml --quiet --stats k.csv", 3, "error: cannot write k.csv: it is a FIFO and no process is reading it\n"},
      {"plot good.csv -o k.svg --quiet", 3, "error: cannot write k.svg: it is a FIFO and no process is reading it\n"},
      {"sweep sweep.yaml -o out --emit parallel --quiet", 3,
       // The sweep's own folder: a FIFO there is refused whether or not someone reads it.
       "error: cannot write " + (s.dir / "out/jobs.csv").string() + ": it is a FIFO; a file of " +
           (s.dir / "out").string() + " is a regular file\n"},
      {"run s.yaml --quiet --record record.txt", 2,
       "error: --record record.txt: not a regular file; a record is a regular file\n"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.args);
    Scratch::Usage usage;
    const Result r = s.runBounded(c.args, usage);  // the old program waited in open() until killed
    CHECK(r.code == c.code);
    CHECK(r.err == c.err);
  }
  for (const char* fifo : {"k.mp4", "k.csv", "k.svg", "out/jobs.csv", "record.txt"}) {
    CAPTURE(fifo);
    CHECK(S_ISFIFO(lstatOf(s.dir / fifo).st_mode));
  }

  // With a reader there, a FIFO is written as before: here the test holds the read end.
  const int reader = ::open((s.dir / "k.csv").c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  REQUIRE(reader >= 0);
  const Result r = s.run("run s.yaml --quiet --duration 0.2 --stats k.csv");
  CHECK_MESSAGE(r.code == 0, r.err);
  char buffer[4096];
  const ssize_t n = ::read(reader, buffer, sizeof buffer);
  ::close(reader);
  REQUIRE(n > 0);
  CHECK(std::string(buffer, size_t(n)) == slurp(s.dir / "good.csv"));
}

// A render writing --trace into a FIFO whose reader holds it open but never reads: once the pipe
// is full every write waits, and the old program, whose handler only set a flag that the blocked
// frame loop never saw again, could be stopped by SIGKILL alone.
TEST_CASE("SIGTERM ends a render whose output blocks") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  const fs::path fifo = s.dir / "trace.csv";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const int held = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);  // a reader that never reads
  REQUIRE(held >= 0);
  const int capacity = ::fcntl(held, F_GETPIPE_SZ);
  REQUIRE(capacity > 0);

  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
  const pid_t pid = ::fork();
  REQUIRE(pid >= 0);
  if (pid == 0) {
    if (::chdir(s.dir.c_str()) != 0) ::_exit(127);
    const int err = ::open("stderr.txt", O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (err < 0 || ::dup2(err, STDERR_FILENO) < 0) ::_exit(127);
    ::execl(exe.c_str(), "particles", "render", "s.yaml", "-o", "x.mp4", "--quiet", "--fps", "1000", "--duration", "30",
            "--trace", "trace.csv", static_cast<char*>(nullptr));
    ::_exit(127);
  }
  // Hang guards only: the test waits for the pipe to fill, then for the exit.
  const auto guard = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  int queued = 0, status = 0;
  pid_t waited = 0;
  while (queued < capacity && std::chrono::steady_clock::now() < guard &&
         (waited = ::waitpid(pid, &status, WNOHANG)) == 0) {
    REQUIRE(::ioctl(held, FIONREAD, &queued) == 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  REQUIRE_MESSAGE(waited == 0, "the render ended before its output blocked: " << slurp(s.dir / "stderr.txt"));
  REQUIRE(queued == capacity);
  ::kill(pid, SIGTERM);
  while ((waited = ::waitpid(pid, &status, WNOHANG)) == 0 && std::chrono::steady_clock::now() < guard) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (waited == 0) {
    ::kill(pid, SIGKILL);
    ::waitpid(pid, &status, 0);
  }
  ::close(held);
  CHECK_MESSAGE(waited == pid, "still running 60 s after SIGTERM");
  CHECK(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 128 + SIGTERM);
  // Ended where it was blocked, by the grace period's alarm; or, had the frame loop seen the
  // signal between two blocking writes, by the loop (and the alarm, should closing --trace block).
  const std::string err = slurp(s.dir / "stderr.txt");
  CHECK_MESSAGE((err.find("particles: not stopped within 3 s of the signal") != std::string::npos ||
                 err.find("s.yaml: interrupted at frame") != std::string::npos),
                err);
  CHECK(S_ISFIFO(lstatOf(fifo).st_mode));
  CHECK_FALSE(fs::exists(s.dir / "x.mp4"));
}
