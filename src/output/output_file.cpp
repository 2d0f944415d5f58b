#include "output/output_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace particles::output {

OutputFile::OutputFile(std::filesystem::path path) : pending_(std::move(path)), file_(pending_.openStream()) {}

OutputFile::OutputFile(const ConfinedFolder& folder, const std::filesystem::path& relative)
    : pending_(folder, relative), file_(pending_.openStream()) {}

void OutputFile::write(std::string_view text) {
  if (std::fwrite(text.data(), 1, text.size(), file_.get()) != text.size()) {
    throw OutputError(fmt::format("cannot write {}: {}", pending_.destination().string(), std::strerror(errno)));
  }
}

void OutputFile::commit() {
  std::FILE* f = file_.release();
  const bool flushed = std::fflush(f) == 0 && !std::ferror(f);
  const int flushErrno = errno;
  const bool closed = std::fclose(f) == 0;
  if (!flushed || !closed) {
    pending_.discard();
    throw OutputError(fmt::format("cannot write {}: {}", pending_.destination().string(),
                                  std::strerror(flushed ? errno : flushErrno)));
  }
  pending_.commit();
}

}  // namespace particles::output
