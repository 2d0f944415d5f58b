// The output room (src/output/): the rule that an output is never an input or another output
// (distinct_files.hpp); what PendingOutput and OutputFile do with what is at the
// destination (nothing, a regular file, a device, a FIFO, a link, a directory, a socket), what is on
// disk while writing, after commit, after discard and after a SIGKILL, and the removal of
// temporaries left by killed runs. Above all: never clobber what is not ours.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>
#include <set>
#include <string>
#include <thread>

#include "cli_support.hpp"
#include "output/distinct_files.hpp"
#include "output/output_file.hpp"
#include "output/partial_names.hpp"
#include "output/pending_output.hpp"
#include "render/video/frame_writer.hpp"
#include "render/png_io.hpp"
#include "support/video_probe.hpp"

using namespace particles::output;
using particles::test::Scratch;
using particles::test::slurp;
namespace fs = std::filesystem;

namespace {

std::set<std::string> entries(const fs::path& dir) {
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.insert(e.path().filename().string());
  return names;
}

struct stat lstatOrFail(const fs::path& path) {
  struct stat st {};
  REQUIRE_MESSAGE(::lstat(path.c_str(), &st) == 0, path << ": " << std::strerror(errno));
  return st;
}

void writeAll(const PendingOutput& out, const std::string& text) {
  REQUIRE(::write(out.fd(), text.data(), text.size()) == ssize_t(text.size()));
}

// Sets the umask for one scope: the process-wide value is put back however the scope ends.
struct ScopedUmask {
  mode_t previous;
  explicit ScopedUmask(mode_t mask) : previous(::umask(mask)) {}
  ~ScopedUmask() { ::umask(previous); }
};

// A pid no process has: a child that has exited and been reaped. (The kernel could hand it out
// again before the test is over, but it counts up through the pid space first.)
pid_t deadPid() {
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  return child;
}

// Runs `body` in a child process; `body` ends by killing the child with SIGKILL while its output is
// still open, as `kill -9` would mid-write. Returns the child's pid once it is dead and reaped.
template <class Body>
pid_t runAndKill(Body body) {
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    try {
      body();
    } catch (...) {
      ::_exit(1);
    }
    ::_exit(2);  // body returned: its output was closed before any kill
  }
  int status = 0;
  REQUIRE(::waitpid(child, &status, 0) == child);
  REQUIRE_MESSAGE(WIFSIGNALED(status), "the child exited with " << WEXITSTATUS(status));
  CHECK(WTERMSIG(status) == SIGKILL);
  return child;
}

}  // namespace

TEST_CASE("output: an anonymous temporary has no name in the folder until commit") {
  Scratch s;
  const fs::path out = s.dir / "x.csv";
  {
    OutputFile file(out);
    file.write("a,b\n1,2\n");
    CHECK(entries(s.dir).empty());
    file.commit();
  }
  CHECK(entries(s.dir) == std::set<std::string>{"x.csv"});
  CHECK(slurp(out) == "a,b\n1,2\n");

  PendingOutput pending(s.dir / "y.bin");
  REQUIRE_MESSAGE(pending.route() == PendingOutput::Route::anonymous, "no O_TMPFILE in " << s.dir);
  CHECK(pending.reopenablePath().string().starts_with("/proc/self/fd/"));
  writeAll(pending, "bytes");
  CHECK(entries(s.dir) == std::set<std::string>{"x.csv"});
  pending.commit();
  CHECK(entries(s.dir) == std::set<std::string>{"x.csv", "y.bin"});
  CHECK(slurp(s.dir / "y.bin") == "bytes");
}

TEST_CASE("output: an uncommitted output leaves nothing, and an existing file as it was") {
  Scratch s;
  const fs::path out = s.dir / "x.csv";
  for (const auto temporary : {PendingOutput::Temporary::anonymousWherePossible, PendingOutput::Temporary::named}) {
    CAPTURE(int(temporary));
    {  // destroyed without commit: an exception unwinding the writer
      PendingOutput pending(out, temporary);
      writeAll(pending, "half");
    }
    CHECK(entries(s.dir).empty());
    {
      PendingOutput pending(out, temporary);
      writeAll(pending, "half");
      pending.discard();
      pending.discard();  // idempotent
      CHECK_THROWS_AS(pending.commit(), std::logic_error);
    }
    CHECK(entries(s.dir).empty());
  }
  s.write("x.csv", "previous run");
  {
    OutputFile file(out);
    file.write("new");
  }
  CHECK(slurp(out) == "previous run");
  CHECK(entries(s.dir) == std::set<std::string>{"x.csv"});
}

// fopen(…, "w") creates a file with 0666 less the umask and keeps an existing file's mode; the
// output's final permissions are the same, however it was written.
TEST_CASE("output: a file gets the permissions fopen would give it") {
  Scratch s;
  const ScopedUmask umask(027);
  std::FILE* reference = std::fopen((s.dir / "by_fopen").c_str(), "w");
  REQUIRE(reference != nullptr);
  std::fclose(reference);
  const mode_t fopenMode = lstatOrFail(s.dir / "by_fopen").st_mode & 07777;
  CHECK(fopenMode == 0640);
  for (const auto temporary : {PendingOutput::Temporary::anonymousWherePossible, PendingOutput::Temporary::named}) {
    CAPTURE(int(temporary));
    const fs::path out = s.dir / "new.csv";
    PendingOutput pending(out, temporary);
    writeAll(pending, "x");
    pending.commit();
    CHECK((lstatOrFail(out).st_mode & 07777) == fopenMode);

    // An existing file keeps its mode when replaced.
    REQUIRE(::chmod(out.c_str(), 0604) == 0);
    PendingOutput again(out, temporary);
    writeAll(again, "y");
    again.commit();
    CHECK((lstatOrFail(out).st_mode & 07777) == 0604);
    CHECK(slurp(out) == "y");
    fs::remove(out);
  }
}

namespace {

// Run as root, a regression here would replace the machine's /dev/null with a regular file: the
// route is checked first, and only an output known to write in place is committed.
void requireWrittenInPlace(const fs::path& device) {
  PendingOutput pending(device);
  REQUIRE(pending.route() == PendingOutput::Route::inPlace);
  writeAll(pending, "dropped");
}  // discarded: a device is only closed, never removed

}  // namespace

TEST_CASE("output: /dev/null is written in place and stays a character device") {
  requireWrittenInPlace("/dev/null");
  CHECK(S_ISCHR(lstatOrFail("/dev/null").st_mode));
  {
    OutputFile file("/dev/null");
    file.write("nothing to see\n");
    file.commit();
  }
  CHECK(S_ISCHR(lstatOrFail("/dev/null").st_mode));
}

// /dev/stdout and /dev/fd/N lead to /proc/self/fd/N: a process's open file, not a path to follow.
TEST_CASE("output: an open descriptor through /dev/fd or /proc is written in place and appended to") {
  int pipeEnds[2];
  REQUIRE(::pipe2(pipeEnds, O_CLOEXEC) == 0);
  {  // a pipe, as stdout is under `particles … | head`
    OutputFile file("/dev/fd/" + std::to_string(pipeEnds[1]));
    file.write("through the pipe\n");
    file.commit();
  }
  ::close(pipeEnds[1]);
  std::string received(64, '\0');
  received.resize(size_t(std::max<ssize_t>(0, ::read(pipeEnds[0], received.data(), received.size()))));
  ::close(pipeEnds[0]);
  CHECK(received == "through the pipe\n");

  // A regular file behind the descriptor (stdout redirected to a file): the same file, appended to.
  Scratch s;
  const fs::path log = s.write("log.txt", "printed before\n");
  const int logFd = ::open(log.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  REQUIRE(logFd >= 0);
  const ino_t inode = lstatOrFail(log).st_ino;
  {
    OutputFile file("/proc/self/fd/" + std::to_string(logFd));
    file.write("t,kinetic\n");
    file.commit();
  }
  ::close(logFd);
  CHECK(slurp(log) == "printed before\nt,kinetic\n");
  CHECK(lstatOrFail(log).st_ino == inode);
  CHECK(entries(s.dir) == std::set<std::string>{"log.txt"});
}

TEST_CASE("output: a FIFO is written in place and its reader gets the data") {
  Scratch s;
  const fs::path fifo = s.dir / "pipe";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // The FIFO is held open for reading and writing (Linux allows it) until the output is done, so
  // the reader's open does not wait and its reads end only when this is closed too. Were the FIFO
  // replaced or refused, the reader would see no data rather than wait forever.
  struct Closer {
    int fd;
    explicit Closer(int descriptor) : fd(descriptor) {}
    Closer(const Closer&) = delete;
    ~Closer() { ::close(fd); }
  };
  std::string received;
  std::jthread reader;  // declared before `keeper`: on every way out, keeper is closed, then this joins
  std::optional<Closer> keeper(std::in_place, ::open(fifo.c_str(), O_RDWR | O_CLOEXEC));
  REQUIRE(keeper->fd >= 0);
  std::FILE* readEnd = std::fopen(fifo.c_str(), "r");
  REQUIRE(readEnd != nullptr);
  reader = std::jthread([&] {
    char buffer[256];
    for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, readEnd)) > 0;) received.append(buffer, n);
    std::fclose(readEnd);
  });
  {
    OutputFile file(fifo);
    file.write("t,kinetic\n");
    file.write("0,1\n");
    file.commit();
  }
  keeper.reset();
  reader.join();
  CHECK(received == "t,kinetic\n0,1\n");
  CHECK(S_ISFIFO(lstatOrFail(fifo).st_mode));
  CHECK(entries(s.dir) == std::set<std::string>{"pipe"});
}

TEST_CASE("output: a symbolic link is followed to its target, and stays a link") {
  Scratch s;
  fs::create_directory(s.dir / "links");
  fs::create_directory(s.dir / "files");
  s.write("files/target.csv", "old");
  fs::create_symlink("../files/target.csv", s.dir / "links" / "link.csv");  // relative to its folder
  fs::create_symlink(s.dir / "links" / "link.csv", s.dir / "links" / "chain.csv");
  fs::create_symlink("../files/new.csv", s.dir / "links" / "dangling.csv");
  const std::set<std::string> links{"link.csv", "chain.csv", "dangling.csv"};

  for (const auto temporary : {PendingOutput::Temporary::anonymousWherePossible, PendingOutput::Temporary::named}) {
    CAPTURE(int(temporary));
    for (const char* name : {"link.csv", "chain.csv"}) {
      CAPTURE(name);
      PendingOutput pending(s.dir / "links" / name, temporary);
      if (pending.route() == PendingOutput::Route::named) {
        // Beside the target, so that the rename stays on its filesystem.
        CHECK(pending.reopenablePath().parent_path() == s.dir / "links" / ".." / "files");
      }
      writeAll(pending, std::string("through ") + name);
      pending.commit();
      CHECK(slurp(s.dir / "files" / "target.csv") == std::string("through ") + name);
    }
    PendingOutput pending(s.dir / "links" / "dangling.csv", temporary);
    writeAll(pending, "created");
    pending.commit();
    CHECK(slurp(s.dir / "files" / "new.csv") == "created");
    CHECK(entries(s.dir / "files") == std::set<std::string>{"target.csv", "new.csv"});
    CHECK(entries(s.dir / "links") == links);
    for (const std::string& link : links) CHECK(S_ISLNK(lstatOrFail(s.dir / "links" / link).st_mode));
    CHECK(fs::read_symlink(s.dir / "links" / "link.csv") == "../files/target.csv");
    fs::remove(s.dir / "files" / "new.csv");
  }

  // A PNG and an MP4 through a link: the libraries write the target too.
  particles::render::writePng(s.dir / "links" / "link.csv", particles::render::Image(8, 6));
  CHECK(particles::render::readPng(s.dir / "files" / "target.csv").width == 8);
  particles::render::setLibavVerbose(false);
  fs::create_symlink("../files/video.mp4", s.dir / "links" / "video.mp4");
  particles::render::FrameWriterOptions options;
  options.width = 64;
  options.height = 48;
  auto writer = particles::render::openFrameWriter(s.dir / "links" / "video.mp4", options);
  for (int i = 0; i < 3; ++i) writer->write(particles::render::Image(64, 48));
  writer->finish();
  CHECK(particles::test::probeVideo(s.dir / "files" / "video.mp4").frames == 3);
  CHECK(S_ISLNK(lstatOrFail(s.dir / "links" / "video.mp4").st_mode));
  CHECK(entries(s.dir / "files") == std::set<std::string>{"target.csv", "video.mp4"});
}

TEST_CASE("output: a directory or a socket is refused and left as it is") {
  Scratch s;
  fs::create_directory(s.dir / "folder");
  fs::create_symlink("folder", s.dir / "to_folder");
  const fs::path socketPath = s.dir / "sock";
  const int sock = ::socket(AF_UNIX, SOCK_STREAM, 0);
  REQUIRE(sock >= 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  REQUIRE(socketPath.string().size() < sizeof address.sun_path);
  std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socketPath.c_str());
  REQUIRE(::bind(sock, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0);

  CHECK_THROWS_WITH_AS(OutputFile(s.dir / "folder"), doctest::Contains("folder: it is a directory"), OutputError);
  const std::string linkMessage = "to_folder (a link to " + (s.dir / "folder").string() + "): it is a directory";
  CHECK_THROWS_WITH_AS(OutputFile(s.dir / "to_folder"), doctest::Contains(linkMessage.c_str()), OutputError);
  CHECK_THROWS_WITH_AS(PendingOutput{socketPath}, doctest::Contains("sock: it is a socket"), OutputError);
  CHECK(fs::is_empty(s.dir / "folder"));
  CHECK(S_ISSOCK(lstatOrFail(socketPath).st_mode));
  CHECK(S_ISLNK(lstatOrFail(s.dir / "to_folder").st_mode));

  // Through the program: exit 3 and the same words.
  s.write("s.yaml", particles::test::kSwingScenario);
  const particles::test::Result r = s.run("run s.yaml --quiet --stats sock");
  CHECK(r.code == 3);
  CHECK(r.err == "error: cannot write sock: it is a socket\n");
  CHECK(S_ISSOCK(lstatOrFail(socketPath).st_mode));
  ::close(sock);
  CHECK(entries(s.dir) == std::set<std::string>{"folder", "to_folder", "sock", "s.yaml"});
}

TEST_CASE("output: the program writes --stats to /dev/null and leaves it a device") {
  requireWrittenInPlace("/dev/null");
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  const particles::test::Result r = s.run("run s.yaml --quiet --stats /dev/null");
  CHECK_MESSAGE(r.code == 0, r.err);
  CHECK(S_ISCHR(lstatOrFail("/dev/null").st_mode));
  CHECK(entries(s.dir) == std::set<std::string>{"s.yaml"});
}

TEST_CASE("output: the program writes --stats to /dev/stdout, a file there is appended to") {
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  // Scratch::run sends stdout to a file: the stats are appended to it, not put in its place.
  const particles::test::Result toStdout = s.run("run s.yaml --quiet --stats /dev/stdout");
  CHECK_MESSAGE(toStdout.code == 0, toStdout.err);
  CHECK(toStdout.out.starts_with("t,kinetic,potential,total,constraint_error,penetration\n"));
  CHECK(S_ISLNK(lstatOrFail("/dev/stdout").st_mode));
  CHECK(entries(s.dir) == std::set<std::string>{"s.yaml"});
}

TEST_CASE("output: a writer killed with SIGKILL leaves no anonymous temporary behind") {
  Scratch s;
  s.write("x.mp4", "previous run");
  runAndKill([&] {
    PendingOutput pending(s.dir / "x.mp4");
    if (pending.route() != PendingOutput::Route::anonymous) throw OutputError("no O_TMPFILE");
    writeAll(pending, "half a video");
    ::raise(SIGKILL);
  });
  CHECK(entries(s.dir) == std::set<std::string>{"x.mp4"});
  CHECK(slurp(s.dir / "x.mp4") == "previous run");
}

TEST_CASE("output: a named temporary left by a killed run is removed by the next output of that name") {
  Scratch s;
  const pid_t killed = runAndKill([&] {
    PendingOutput pending(s.dir / "x.csv", PendingOutput::Temporary::named);
    writeAll(pending, "half");
    ::raise(SIGKILL);
  });
  const std::set<std::string> left = entries(s.dir);
  REQUIRE(left.size() == 1);
  CHECK(left.begin()->starts_with("x.csv.partial-" + std::to_string(killed) + "-"));
  OutputFile file(s.dir / "x.csv");
  file.write("whole");
  file.commit();
  CHECK(entries(s.dir) == std::set<std::string>{"x.csv"});
}

TEST_CASE("output: stale temporaries are removed only by their exact pattern, dead pid and owner") {
  Scratch s;
  const std::string dead = std::to_string(deadPid()), own = std::to_string(::getpid());
  s.write("x.mp4.partial-" + dead + "-0", "stale");
  fs::create_directory(s.dir / ("x.mp4.partial-" + dead + "-3"));  // a PNG sequence's staging directory
  s.write("x.mp4.partial-" + dead + "-3/frame_000000.png", "stale frame");
  const std::set<std::string> kept{
      "x.mp4.partial-" + own + "-7",    // a live run (this one)
      "x.mp4.partial-abc",              // not our pattern
      "x.mp4.partial-" + dead + "-1x",  // not our pattern
      "x.mp4.partial--" + dead + "-1",  // not our pattern
      "x.mp4.partial-0-1",              // pid 0 is no process
      "y.mp4.partial-" + dead + "-0",   // another output's: left to the next run writing y.mp4
      "xx.mp4.partial-" + dead + "-0",  // another output's
      "x.mp4.partial-" + dead + "-5",   // a link, not a file we wrote
      "x.mp4.partial-" + dead + "-6",   // another user's (checked when running as root)
      "notes.txt",
  };
  for (const std::string& name : kept) {
    if (name == "x.mp4.partial-" + dead + "-5") {
      fs::create_symlink("notes.txt", s.dir / name);
    } else {
      s.write(name, "keep");
    }
  }
  const bool canChown = ::geteuid() == 0;
  if (canChown) REQUIRE(::chown((s.dir / ("x.mp4.partial-" + dead + "-6")).c_str(), 65534, 65534) == 0);

  PendingOutput pending(s.dir / "x.mp4", PendingOutput::Temporary::named);  // the fallback route
  writeAll(pending, "video");
  pending.commit();
  std::set<std::string> expected = kept;
  expected.insert("x.mp4");
  if (!canChown) expected.erase("x.mp4.partial-" + dead + "-6");
  CHECK(entries(s.dir) == expected);
  CHECK(slurp(s.dir / "notes.txt") == "keep");
  CHECK(removeStalePartials(s.dir, "x.mp4") == 0);
  CHECK(removeStalePartials(s.dir, "y.mp4") == 1);
}

// The rule of distinct_files.hpp. Each case is a pair a comparison of the names as given would
// let through; all paths are absolute (the test does not chdir), `..` and links do the rest.
TEST_CASE("output: an output that is an input or another output is refused, however it is named") {
  Scratch s;
  s.write("a.csv", "input");
  fs::create_directory(s.dir / "d");
  fs::create_directory(s.dir / "real");
  fs::create_directory(s.dir / "real" / "inner");
  s.write("real/x.csv", "x");
  fs::create_symlink("a.csv", s.dir / "link.csv");
  fs::create_symlink("real/inner", s.dir / "sub");  // sub/.. is real/, not the scratch folder
  fs::create_hard_link(s.dir / "a.csv", s.dir / "hard.csv");
  fs::create_symlink("new.csv", s.dir / "dangling.csv");
  const fs::path a = s.dir / "a.csv";

  auto refused = [](const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs) {
    try {
      requireDistinctFiles(outputs, inputs);
    } catch (const SameFileError& e) {
      return std::string(e.what());
    }
    return std::string();
  };

  SUBCASE("an existing file, through .., a link, a hard link or a linked folder's ..") {
    for (const fs::path& other : {s.dir / "d" / ".." / "a.csv", s.dir / "." / "link.csv", s.dir / "hard.csv"}) {
      CAPTURE(other);
      CHECK(refused({{"--record", other}}, {{"the scenario", a}}) ==
            "--record '" + other.string() + "' and the scenario '" + a.string() +
                "' name the same file; an output never replaces an input");
      CHECK(refused({{"--stats", a}, {"--trace", other}}, {}) ==
            "--stats '" + a.string() + "' and --trace '" + other.string() +
                "' name the same file; an output never replaces another output");
    }
    CHECK(!refused({{"-o", s.dir / "sub" / ".." / "x.csv"}}, {{"input", s.dir / "real" / "x.csv"}}).empty());
    CHECK(refused({{"-o", s.dir / "sub" / ".." / "x.csv"}}, {{"input", s.dir / "x.csv"}}).empty());
  }
  SUBCASE("outputs that do not exist yet, by the name they would be created under") {
    const fs::path made = s.dir / "new.csv";
    for (const fs::path& other :
         {s.dir / "d" / ".." / "new.csv", s.dir / "dangling.csv", s.dir / "real" / ".." / "new.csv"}) {
      CAPTURE(other);
      CHECK(!refused({{"--stats", made}, {"--record", other}}, {}).empty());
    }
    CHECK(!refused({{"-o", s.dir / "sub" / ".." / "y.csv"}, {"--plot", s.dir / "real" / "y.csv"}}, {}).empty());
    CHECK(!refused({{"-o", s.dir / "frames/"}, {"--record", s.dir / "frames"}}, {}).empty());
    // An input that is not there yet (a record a job has not written) is compared the same way.
    CHECK(!refused({{"-o", s.dir / "d" / "r.txt"}}, {{"record", s.dir / "real" / ".." / "d" / "r.txt"}}).empty());
  }
  SUBCASE("different files, devices and options not given pass") {
    CHECK(refused({{"--stats", a}, {"--trace", s.dir / "real" / "x.csv"}, {"--record", s.dir / "new.csv"}},
                  {{"the scenario", s.dir / "d" / "s.yaml"}}) == "");
    CHECK(refused({{"--stats", "/dev/null"}, {"--trace", "/dev/null"}}, {}) == "");
    CHECK(refused({{"--stats", a}, {"--trace", ""}}, {{"the scenario", ""}}) == "");
    CHECK(refused({{"-o", s.dir / "j.mp4"}}, {{"segment", a}, {"segment", s.dir / "link.csv"}}) == "");
  }
  CHECK(sameFile(s.dir / "link.csv", s.dir / "hard.csv"));
  CHECK(!sameFile(s.dir / "link.csv", s.dir / "real" / "x.csv"));
  CHECK(slurp(a) == "input");
}
