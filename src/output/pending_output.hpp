#pragma once
// An output written under a temporary name beside its destination and renamed over it only when
// complete, so a reader never sees a half-written file and an existing output is replaced only
// on success. The temporary name is "<destination>.partial-<pid>-<n>"; if the process is killed
// outright (SIGKILL) that file is what is left behind, and its name says what it is.

#include <filesystem>

namespace particles::output {

class PendingOutput {
 public:
  explicit PendingOutput(std::filesystem::path destination);
  ~PendingOutput();  // discards the temporary unless committed
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;

  const std::filesystem::path& destination() const { return destination_; }
  const std::filesystem::path& temporary() const { return temporary_; }
  // rename(temporary, destination), atomically replacing a file already there. Throws OutputError.
  void commit();
  // Removes the temporary (file or directory tree) if it exists; never throws.
  void discard() noexcept;

 private:
  std::filesystem::path destination_, temporary_;
  bool done_ = false;
};

}  // namespace particles::output
