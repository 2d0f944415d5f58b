#include "output/staging_directory.hpp"

#include <fmt/format.h>

#include <string>
#include <system_error>
#include <utility>

#include "output/output_error.hpp"
#include "output/partial_names.hpp"

namespace particles::output {

namespace fs = std::filesystem;

StagingDirectory::StagingDirectory(const fs::path& beside) {
  removeStalePartials(beside.has_parent_path() ? beside.parent_path() : fs::path("."), beside.filename().string());
  path_ = nextPartialPath(beside);
  std::error_code ec;
  if (!fs::create_directory(path_, ec)) {
    const fs::path failed = std::exchange(path_, {});  // not ours: discard() must not remove it
    throw OutputError(
        fmt::format("cannot create {}: {}", failed.string(), ec ? ec.message() : std::string("it exists already")));
  }
}

StagingDirectory::~StagingDirectory() {
  discard();
}

void StagingDirectory::discard() noexcept {
  if (path_.empty()) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
  path_.clear();
}

}  // namespace particles::output
