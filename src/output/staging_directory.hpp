#pragma once
// A directory to gather files in before they are moved to where they belong (the frames of a PNG
// sequence): "<beside>.partial-<pid>-<n>" (partial_names.hpp), created empty, removed with
// whatever is left in it when the object dies. Staging directories that killed runs left beside
// the same name are removed first. There is no anonymous directory in POSIX, so a run killed
// outright leaves this one behind, for the next run to remove.

#include <filesystem>
#include <utility>

namespace particles::output {

class StagingDirectory {
 public:
  // Throws OutputError naming the directory when it cannot be created.
  explicit StagingDirectory(const std::filesystem::path& beside);
  ~StagingDirectory();  // discard()
  StagingDirectory(const StagingDirectory&) = delete;
  StagingDirectory& operator=(const StagingDirectory&) = delete;

  const std::filesystem::path& path() const { return path_; }
  // Removes the directory and everything in it; never throws, idempotent.
  void discard() noexcept;
  // Gives the directory up (it was renamed into place, or now holds what its caller keeps or
  // removes itself): the destructor leaves that path alone. Returns the path.
  std::filesystem::path release() noexcept { return std::exchange(path_, {}); }

 private:
  std::filesystem::path path_;
};

}  // namespace particles::output
