// Files beneath a folder, reached from its descriptor: see confined_folder.hpp.
#include "output/confined_folder.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <deque>
#include <vector>

#include "output/output_error.hpp"
#include "output/output_file.hpp"
#include "output/system_limits.hpp"

namespace particles::output {

namespace fs = std::filesystem;

namespace {

EntryKind kindOfMode(mode_t mode) {
  if (S_ISREG(mode)) return EntryKind::regular;
  if (S_ISDIR(mode)) return EntryKind::directory;
  if (S_ISLNK(mode)) return EntryKind::symlink;
  return EntryKind::other;
}

// The components of a relative path, in order ("a/./b//c" → a, ., b, c; the empty ones dropped).
void pushComponents(std::deque<std::string>& pending, const fs::path& path, bool atFront) {
  std::vector<std::string> parts;
  for (const fs::path& part : path) {
    if (!part.empty() && part != "/") parts.push_back(part.string());
  }
  if (atFront) {
    pending.insert(pending.begin(), parts.begin(), parts.end());
  } else {
    pending.insert(pending.end(), parts.begin(), parts.end());
  }
}

std::string readLinkAt(int folder, const std::string& name, const fs::path& shown) {
  std::string target(256, '\0');
  for (;;) {
    const ssize_t n = ::readlinkat(folder, name.c_str(), target.data(), target.size());
    if (n < 0) throw OutputError(fmt::format("cannot read the link {}: {}", shown.string(), errnoText(errno)));
    if (size_t(n) < target.size()) {
      target.resize(size_t(n));
      return target;
    }
    target.resize(target.size() * 2);
  }
}

}  // namespace

void FileDescriptor::reset() noexcept {
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
}

ConfinedFolder::ConfinedFolder(fs::path root, Create create) : root_(std::move(root)) {
  if (root_.empty()) root_ = ".";
  if (create == Create::yes) {
    std::error_code ec;
    fs::create_directories(root_, ec);
    if (ec) throw OutputError(fmt::format("cannot create {}: {}", root_.string(), ec.message()));
  }
  fd_ = FileDescriptor(::open(root_.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!fd_.valid()) {
    throw OutputError(fmt::format("cannot open the folder {}: {}", root_.string(),
                                  errno == ENOTDIR ? std::string("not a folder") : errnoText(errno)));
  }
}

fs::path ConfinedFolder::shown(const fs::path& relative) const {
  return (root_ / relative).lexically_normal();
}

PlacedName ConfinedFolder::place(const fs::path& relative, bool followLast, Create create) const {
  if (relative.empty() || relative.is_absolute()) {
    throw OutsideFolderError(fmt::format("{}: {} path; a file of {} is named relative to it", relative.string(),
                                         relative.empty() ? "an empty" : "an absolute", root_.string()));
  }
  // The folders walked so far, the root first: `..` goes back one, and never above the root.
  std::vector<FileDescriptor> folders;
  folders.emplace_back(::fcntl(fd_.get(), F_DUPFD_CLOEXEC, 0));
  if (!folders.back().valid()) throw OutputError(fmt::format("dup of {}: {}", root_.string(), errnoText(errno)));
  std::vector<std::string> walked;  // the names of folders[1…], for messages
  auto here = [&](const std::string& name) {
    fs::path p = root_;
    for (const std::string& w : walked) p /= w;
    return name.empty() ? p : p / name;
  };
  std::deque<std::string> pending;
  pushComponents(pending, relative, false);
  int hops = 0;
  while (!pending.empty()) {
    const std::string name = pending.front();
    pending.pop_front();
    if (name == ".") continue;
    if (name == "..") {
      if (folders.size() == 1) {
        throw OutsideFolderError(
            fmt::format("{}: leads outside {} ('..' above it)", shown(relative).string(), root_.string()));
      }
      folders.pop_back();
      walked.pop_back();
      continue;
    }
    const bool last = pending.empty();
    const int folder = folders.back().get();
    struct stat st {};
    if (::fstatat(folder, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0) {
      const int error = errno;
      if (error != ENOENT) throw OutputError(fmt::format("cannot reach {}: {}", here(name).string(), errnoText(error)));
      if (last || create == Create::no) {
        return {std::move(folders.back()), name, EntryKind::absent, here(name)};
      }
      if (::mkdirat(folder, name.c_str(), 0777) != 0 && errno != EEXIST) {
        throw OutputError(fmt::format("cannot create {}: {}", here(name).string(), errnoText(errno)));
      }
      pending.push_front(name);  // look again at what is there now
      continue;
    }
    if (S_ISLNK(st.st_mode) && (!last || followLast)) {
      if (++hops > kMaxLinkHops)
        throw OutputError(fmt::format("cannot reach {}: {}", here(name).string(), errnoText(ELOOP)));
      const std::string target = readLinkAt(folder, name, here(name));
      if (target.empty() || target.front() == '/') {
        throw OutsideFolderError(
            fmt::format("{}: leads outside {} (a symbolic link to {})", here(name).string(), root_.string(), target));
      }
      // The target is walked from the folder holding the link, before what followed the link; a
      // `..` in it that rises above the root is refused like any other.
      pushComponents(pending, target, true);
      continue;
    }
    if (last) return {std::move(folders.back()), name, kindOfMode(st.st_mode), here(name)};
    if (!S_ISDIR(st.st_mode)) {
      throw OutputError(
          fmt::format("cannot reach {}: {} is not a folder", shown(relative).string(), here(name).string()));
    }
    FileDescriptor next(::openat(folder, name.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (!next.valid()) {
      // ELOOP or ENOTDIR: it became a link or a file since fstatat looked; the walk stops.
      throw OutputError(fmt::format("cannot reach {}: {}", here(name).string(), errnoText(errno)));
    }
    folders.push_back(std::move(next));
    walked.push_back(name);
  }
  // The path ended on a folder ("a/b/.." or "."): the folder itself, named by "." within it.
  return {std::move(folders.back()), ".", EntryKind::directory, here("")};
}

EntryKind ConfinedFolder::kindOf(const fs::path& relative) const {
  try {
    return place(relative, true).kind;  // OutsideFolderError, no OutputError, goes on to the caller
  } catch (const OutputError&) {
    return EntryKind::absent;  // a file where a folder should be: nothing of that name
  }
}

FileDescriptor ConfinedFolder::openFolder(const fs::path& relative, Create create) const {
  PlacedName placed = place(relative, true, create);
  if (placed.kind == EntryKind::absent && create == Create::yes) {
    if (::mkdirat(placed.folder.get(), placed.name.c_str(), 0777) != 0 && errno != EEXIST) {
      throw OutputError(fmt::format("cannot create {}: {}", placed.shown.string(), errnoText(errno)));
    }
    placed = place(relative, true, create);
  }
  if (placed.kind != EntryKind::directory) {
    throw OutputError(fmt::format("{}: {}", placed.shown.string(),
                                  placed.kind == EntryKind::absent ? "no such folder" : "not a folder"));
  }
  FileDescriptor fd(::openat(placed.folder.get(), placed.name.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
  if (!fd.valid()) throw OutputError(fmt::format("cannot open {}: {}", placed.shown.string(), errnoText(errno)));
  return fd;
}

void ConfinedFolder::writeFile(const fs::path& relative, std::string_view bytes) const {
  OutputFile out(*this, relative);
  out.write(bytes);
  out.commit();
}

bool ConfinedFolder::remove(const fs::path& relative) const {
  const PlacedName placed = place(relative, false);
  if (placed.kind == EntryKind::absent) return false;
  const int flags = placed.kind == EntryKind::directory ? AT_REMOVEDIR : 0;
  if (::unlinkat(placed.folder.get(), placed.name.c_str(), flags) != 0) {
    throw OutputError(fmt::format("cannot remove {}: {}", placed.shown.string(), errnoText(errno)));
  }
  return true;
}

fs::path relativeBeneath(const fs::path& path, const fs::path& folder) {
  const fs::path p = fs::absolute(path).lexically_normal(), f = fs::absolute(folder).lexically_normal();
  const fs::path rel = p.lexically_relative(f);
  if (rel.empty() || *rel.begin() == ".." || rel == ".") return {};
  return rel;
}

}  // namespace particles::output
