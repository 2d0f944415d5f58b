// input::readTextFile: the one reader of input files (scenarios, stats CSVs). The limit holds for
// regular files (from their size, before reading), for pipes that never end, and a NUL byte ends
// the reading at once.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <cstdio>
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
  std::thread writer([&] {
    std::FILE* out = std::fopen(fifo.c_str(), "wb");
    REQUIRE(out != nullptr);
    const std::string block(4096, 'a');
    // Writes until the reader has gone (EPIPE; SIGPIPE is ignored below) or far past the limit.
    for (int i = 0; i < 4096 && std::fwrite(block.data(), 1, block.size(), out) == block.size(); ++i) {
    }
    std::fclose(out);
  });
  std::string message;
  const auto previous = std::signal(SIGPIPE, SIG_IGN);
  CHECK(reasonOf(fifo, 1, message) == ReadError::Reason::tooLarge);
  writer.join();
  std::signal(SIGPIPE, previous);
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
