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

std::string readFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept, Content content) {
  const std::uintmax_t limit = maxMiB * 1024 * 1024;
  // Opening a FIFO for reading waits for a writer, unless non-blocking: then it returns at once.
  const int flags = O_RDONLY | O_CLOEXEC | (accept == Accept::regularOnly ? O_NONBLOCK : 0);
  const Descriptor in{::open(file.c_str(), flags)};
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
