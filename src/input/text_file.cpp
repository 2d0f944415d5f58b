#include "input/text_file.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace particles::input {

namespace {

// Closes the descriptor on every way out.
struct Descriptor {
  int fd;
  ~Descriptor() {
    if (fd >= 0) ::close(fd);
  }
};

[[noreturn]] void tooLarge(std::uintmax_t maxMiB) {
  throw ReadError(ReadError::Reason::tooLarge,
                  fmt::format("the file is larger than the input limit of {} MiB; if it is meant to be, raise the "
                              "limit with --max-input MIB",
                              maxMiB));
}

enum class Content { text, binary };

void setBlocking(int fd) {
  const int flags = ::fcntl(fd, F_GETFL);
  if (flags < 0 || ::fcntl(fd, F_SETFL, flags & ~O_NONBLOCK) < 0) {
    throw ReadError(ReadError::Reason::readFailed, fmt::format("cannot read: {}", std::strerror(errno)));
  }
}

std::string readFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept, Content content) {
  const std::uintmax_t limit = maxMiB * 1024 * 1024;
  // Opening a FIFO for reading waits for a writer, unless non-blocking: then it returns at once.
  const Descriptor in{::open(file.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK)};
  if (in.fd < 0) {
    throw ReadError(errno == EISDIR ? ReadError::Reason::isDirectory : ReadError::Reason::cannotOpen,
                    fmt::format("cannot open: {}", std::strerror(errno)));
  }
  struct stat info {};
  if (::fstat(in.fd, &info) != 0) {
    throw ReadError(ReadError::Reason::readFailed, fmt::format("cannot read: {}", std::strerror(errno)));
  }
  if (S_ISDIR(info.st_mode)) throw ReadError(ReadError::Reason::isDirectory, "cannot read: it is a directory");
  const bool regular = S_ISREG(info.st_mode);
  if (accept == Accept::regularOnly && !regular) {
    const char* kind = S_ISFIFO(info.st_mode)   ? "a FIFO"
                       : S_ISSOCK(info.st_mode) ? "a socket"
                       : S_ISCHR(info.st_mode)  ? "a character device"
                       : S_ISBLK(info.st_mode)  ? "a block device"
                                                : "not a plain file";
    throw ReadError(ReadError::Reason::notRegular,
                    fmt::format("cannot read: it is {}, where a regular file was expected", kind));
  }
  if (regular && std::uintmax_t(info.st_size) > limit) tooLarge(maxMiB);
  // A FIFO (a named pipe, /dev/stdin from a pipe) whose writer has gone, or never came, would block
  // a read forever: it is refused at once, as outputs refuse a FIFO with no reader. Its first read
  // is still non-blocking and says which: data, or EAGAIN (a writer is there; one blocked in open()
  // waiting for a reader counts already: Linux's fifo_open), or 0 (none). Then, and for everything
  // else at once, reads wait for data as usual.
  bool awaitingWriter = S_ISFIFO(info.st_mode);
  if (!awaitingWriter) setBlocking(in.fd);

  // A regular file's size is known (it may still grow while read: the limit holds anyway); other
  // inputs grow the buffer geometrically, never past limit + 1 bytes.
  std::string text;
  text.resize(regular ? std::size_t(info.st_size) + 1 : std::min<std::uintmax_t>(limit + 1, 1 << 16));
  std::size_t used = 0;
  for (;;) {
    if (used == text.size()) {
      if (used > limit) tooLarge(maxMiB);
      text.resize(std::size_t(std::min<std::uintmax_t>(limit + 1, 2 * std::uintmax_t(text.size()))));
    }
    const ssize_t n = ::read(in.fd, text.data() + used, text.size() - used);
    if (n < 0 && errno == EINTR) continue;
    if (awaitingWriter) {
      if (n == 0) {
        throw ReadError(ReadError::Reason::noWriter,
                        "cannot read: it is a FIFO (a named pipe) with no writer, so nothing can arrive; start "
                        "its writer first");
      }
      if (n < 0 && errno != EAGAIN) {
        throw ReadError(ReadError::Reason::readFailed, fmt::format("cannot read: {}", std::strerror(errno)));
      }
      awaitingWriter = false;
      setBlocking(in.fd);
      if (n < 0) continue;
    }
    if (n < 0) throw ReadError(ReadError::Reason::readFailed, fmt::format("cannot read: {}", std::strerror(errno)));
    if (n == 0) break;
    if (const void* nul = content == Content::text ? std::memchr(text.data() + used, '\0', std::size_t(n)) : nullptr) {
      const std::size_t at = std::size_t(static_cast<const char*>(nul) - text.data());
      throw ReadError(ReadError::Reason::notText,
                      fmt::format("byte {} is a NUL byte, which no text holds: this is not a text file", at + 1));
    }
    used += std::size_t(n);
  }
  if (used > limit) tooLarge(maxMiB);
  text.resize(used);
  return text;
}

}  // namespace

std::string readTextFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept) {
  return readFile(file, maxMiB, accept, Content::text);
}

std::string readBinaryFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept) {
  return readFile(file, maxMiB, accept, Content::binary);
}

}  // namespace particles::input
