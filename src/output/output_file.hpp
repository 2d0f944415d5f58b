#pragma once
// A text output file (the CSVs) written through PendingOutput: it appears whole on commit() or
// not at all, replaces a regular file only then, writes a device or FIFO (/dev/null, a named
// pipe) in place, follows a symbolic link to its target, and refuses a directory, a socket or a
// FIFO that no process is reading.
// Failures throw OutputError (exit code 3).

#include <filesystem>
#include <string_view>

#include "output/output_error.hpp"
#include "output/pending_output.hpp"

namespace particles::output {

class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path path);
  // A file of a folder the command owns, reached beneath it (PendingOutput's confined form).
  OutputFile(const ConfinedFolder& folder, const std::filesystem::path& relative);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view text);
  // Flushes and closes the stream, then publishes the file (PendingOutput::commit).
  void commit();
  const std::filesystem::path& path() const { return pending_.destination(); }

 private:
  PendingOutput pending_;  // declared first: the stream is closed before the file is discarded
  FilePtr file_;
};

}  // namespace particles::output
