#pragma once
// Reading a text file nobody reviewed (a scenario, a stats CSV) without trusting its size: a
// regular file past the limit is refused from its size before a byte is read, anything else (a
// pipe, /dev/stdin, an endless device) is read only until it passes the limit, and a NUL byte, which
// no text holds, ends the reading at once (so /dev/zero or a binary file is refused in its first
// block instead of after 64 MiB).
// The input room depends on nothing; the scenario loader and the figures wrap its ReadError in
// their own error types, so the message says which file and, here, why.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace particles::input {

// The most a text input may take unless `--max-input MIB` says otherwise: a scenario, a stats CSV,
// a sweep file, a job table or record. The demos are a few kB, and an endless input (/dev/zero)
// must end in an error, not in memory.
inline constexpr std::uintmax_t kDefaultMaxInputMiB = 64;

// Why a file could not be read, in words that follow "FILE: error: " ("cannot open: No such file
// or directory"); reason() for callers that act on it.
class ReadError : public std::runtime_error {
 public:
  enum class Reason { cannotOpen, isDirectory, notRegular, noWriter, tooLarge, notText, readFailed };
  ReadError(Reason reason, const std::string& message) : std::runtime_error(message), reason_(reason) {}
  Reason reason() const { return reason_; }

 private:
  Reason reason_;
};

// Which files a reader takes. A scenario or a CSV may come from a pipe (`particles check
// /dev/stdin`), though not from a FIFO with no writer (refused at once, never waited on); a file the program wrote
// itself (a job record, a sweep's jobs.csv) is a regular file, so anything else at its path (a FIFO, a device, a
// socket) was put there by someone else and is refused without blocking: opened non-blocking, checked, never read.
enum class Accept { anyFile, regularOnly };

// The whole of `file`, at most maxMiB mebibytes and without NUL bytes; throws ReadError. The
// message for a file past the limit names the option that raises it, `--max-input MIB`.
std::string readTextFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept = Accept::anyFile);

// The same for a file that is not text (a reference frame's PNG): NUL bytes are kept.
std::string readBinaryFile(const std::filesystem::path& file, std::uintmax_t maxMiB, Accept accept = Accept::anyFile);

}  // namespace particles::input
