// input::readTextFile: the one reader of input files (scenarios, stats CSVs). The limit holds for
// regular files (from their size, before reading), for pipes that never end, and a NUL byte ends
// the reading at once.
#include <doctest/doctest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "input/text_file.hpp"

namespace fs = std::filesystem;
using particles::input::ReadError;
using particles::input::readTextFile;

namespace {

struct TextFileDir {
  fs::path dir;
  TextFileDir() {
    std::string pattern = (fs::temp_directory_path() / "particles_text_file_XXXXXX").string();
    REQUIRE(::mkdtemp(pattern.data()) != nullptr);
    dir = pattern;
  }
  ~TextFileDir() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir / name, std::ios::binary) << text;
    return dir / name;
  }
};

ReadError::Reason reasonOf(const fs::path& file, std::uintmax_t maxMiB, std::string& message) {
  try {
    readTextFile(file, maxMiB);
  } catch (const ReadError& e) {
    message = e.what();
    return e.reason();
  }
  FAIL("read " << file << " without an error");
  return ReadError::Reason::readFailed;
}

}  // namespace

TEST_CASE("text file: up to the limit is read whole, one byte more is refused before reading") {
  TextFileDir t;
  const std::string mib(1024 * 1024, 'x');
  CHECK(readTextFile(t.write("small.yaml", "name: a\n"), 1) == "name: a\n");
  CHECK(readTextFile(t.write("exact.yaml", mib), 1) == mib);
  CHECK(readTextFile(t.write("empty.yaml", ""), 1).empty());
  std::string message;
  CHECK(reasonOf(t.write("over.yaml", mib + "y"), 1, message) == ReadError::Reason::tooLarge);
  CHECK(message ==
        "the file is larger than the input limit of 1 MiB; if it is meant to be, raise the limit with --max-input MIB");
}

TEST_CASE("text file: a pipe that never ends is refused once past the limit") {
  TextFileDir t;
  const fs::path fifo = t.dir / "endless";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  // The writer is there before the reader opens (a FIFO without one is refused at once, below): a
  // reader of the test's own lets its open return, and holds the FIFO open until the end, so that
  // the writer's writes, non-blocking, never wait on a full pipe.
  const int keeper = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  REQUIRE(keeper >= 0);
  const int out = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  REQUIRE(out >= 0);
  std::atomic<bool> done{false};
  std::thread writer([&] {
    const std::string block(4096, 'a');
    while (!done.load()) {
      if (::write(out, block.data(), block.size()) < 0 && errno != EAGAIN) break;
      std::this_thread::yield();
    }
    ::close(out);
  });
  std::string message;
  CHECK(reasonOf(fifo, 1, message) == ReadError::Reason::tooLarge);
  done.store(true);
  writer.join();
  ::close(keeper);
}

TEST_CASE("text file: a FIFO with no writer is refused at once, one with a writer read to its end") {
  TextFileDir t;
  const fs::path fifo = t.dir / "scenario.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  std::string message;
  CHECK(reasonOf(fifo, 1, message) == ReadError::Reason::noWriter);
  CHECK(message == "cannot read: it is a FIFO (a named pipe) with no writer, so nothing can arrive; start its writer "
                   "first");
  // A writer that wrote and left: what it wrote is read (the pipe keeps it while a reader holds it).
  const int keeper = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  REQUIRE(keeper >= 0);
  const int out = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
  REQUIRE(out >= 0);
  REQUIRE(::write(out, "name: a\n", 8) == 8);
  ::close(out);
  CHECK(readTextFile(fifo, 1) == "name: a\n");
  ::close(keeper);
}

TEST_CASE("text file: a NUL byte, a directory, a missing file") {
  TextFileDir t;
  std::string message;
  CHECK(reasonOf(t.write("nul.yaml", std::string("name: a\n\0rest", 13)), 1, message) == ReadError::Reason::notText);
  CHECK(message == "byte 9 is a NUL byte, which no text holds: this is not a text file");
  CHECK(reasonOf("/dev/zero", 64, message) == ReadError::Reason::notText);
  CHECK(reasonOf(t.dir, 1, message) == ReadError::Reason::isDirectory);
  CHECK(message == "cannot read: it is a directory");
  CHECK(reasonOf(t.dir / "missing.yaml", 1, message) == ReadError::Reason::cannotOpen);
  CHECK(message == "cannot open: No such file or directory");
}

TEST_CASE("text file: regular files only, for files the program wrote itself: a FIFO or device is refused at once") {
  using particles::input::Accept;
  TextFileDir t;
  const fs::path fifo = t.dir / "record.txt";
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  // With nobody writing, a blocking open would wait for ever: this must return at once.
  try {
    readTextFile(fifo, 1, Accept::regularOnly);
    FAIL("a FIFO was read");
  } catch (const ReadError& e) {
    CHECK(e.reason() == ReadError::Reason::notRegular);
    CHECK(std::string(e.what()) == "cannot read: it is a FIFO, where a regular file was expected");
  }
  try {
    readTextFile("/dev/zero", 1, Accept::regularOnly);
    FAIL("a device was read");
  } catch (const ReadError& e) {
    CHECK(e.reason() == ReadError::Reason::notRegular);
    CHECK(std::string(e.what()).find("a character device") != std::string::npos);
  }
  CHECK(readTextFile(t.write("ok.txt", "version: 1\n"), 1, Accept::regularOnly) == "version: 1\n");
  const fs::path link = t.dir / "link.txt";
  fs::create_symlink(t.dir / "ok.txt", link);
  CHECK(readTextFile(link, 1, Accept::regularOnly) == "version: 1\n");  // a link to a regular file is one
}
