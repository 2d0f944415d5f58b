#include "output_file.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace particles::cli {

OutputFile::OutputFile(std::filesystem::path path) : path_(std::move(path)) {
  if (path_.empty()) throw OutputError("cannot write to an empty file name");
  std::error_code ec;
  if (std::filesystem::is_directory(path_, ec)) {
    throw OutputError(fmt::format("cannot write {}: it is a directory", path_.string()));
  }
  // In the destination's directory, so that the final rename stays on one file system.
  temporary_ = path_;
  temporary_ += fmt::format(".tmp{}", ::getpid());
  file_.reset(std::fopen(temporary_.c_str(), "wb"));
  if (!file_) throw OutputError(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
}

OutputFile::~OutputFile() {
  if (committed_) return;
  file_.reset();
  std::error_code ignored;
  std::filesystem::remove(temporary_, ignored);
}

void OutputFile::write(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), file_.get()) != text.size()) {
    throw OutputError(fmt::format("cannot write {}: {}", path_.string(), std::strerror(errno)));
  }
}

void OutputFile::commit() {
  std::FILE* f = file_.release();
  const bool flushed = std::fflush(f) == 0 && !std::ferror(f);
  const int flushErrno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!flushed || !closed) {
    throw OutputError(fmt::format("cannot write {}: {}", path_.string(), std::strerror(flushed ? errno : flushErrno)));
  }
  std::error_code ec;
  std::filesystem::rename(temporary_, path_, ec);
  if (ec) throw OutputError(fmt::format("cannot write {}: {}", path_.string(), ec.message()));
  committed_ = true;
}

}  // namespace particles::cli
