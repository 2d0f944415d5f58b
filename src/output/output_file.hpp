#pragma once
// A text output file (the CSVs) written under a temporary name next to its destination and renamed
// over it only on commit() (PendingOutput), so that a failed or interrupted run never
// leaves a truncated file behind; an uncommitted file is removed when the object dies. Failures
// throw OutputError (exit code 3).

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string_view>

#include "output/output_error.hpp"
#include "output/pending_output.hpp"

namespace particles::output {

class OutputFile {
 public:
  explicit OutputFile(std::filesystem::path path);
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  void write(std::string_view text);
  // Flushes, closes and renames onto the destination.
  void commit();
  const std::filesystem::path& path() const { return pending_.destination(); }

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  PendingOutput pending_;  // declared first: the file is closed before it is removed
  std::unique_ptr<std::FILE, Closer> file_;
};

}  // namespace particles::output
