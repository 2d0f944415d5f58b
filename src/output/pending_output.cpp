#include "output/pending_output.hpp"

#include <fcntl.h>
#include <fmt/format.h>
#include <linux/magic.h>
#include <sys/stat.h>
#include <sys/vfs.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "output/output_error.hpp"
#include "output/partial_names.hpp"
#include "output/system_limits.hpp"

namespace particles::output {

namespace fs = std::filesystem;

namespace {

// For messages: what a path that is not a regular file is.
const char* fileKind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

fs::path folderOf(const fs::path& file) {
  return file.has_parent_path() ? file.parent_path() : fs::path(".");
}

// A link in /proc (/proc/self/fd/1, where /dev/stdout and /dev/fd/1 lead) is not a path to a file
// but a process's open file: what readlink shows ("pipe:[1234]", "/dev/pts/0") need not be a name
// that opens anything, and a regular file behind it (stdout redirected to a file) is the shell's,
// not ours to replace.
bool isProcLink(const fs::path& link) {
  struct statfs filesystem {};
  return ::statfs(folderOf(link).c_str(), &filesystem) == 0 && filesystem.f_type == PROC_SUPER_MAGIC;
}

}  // namespace

// Links in the folders on the way need no help: the kernel follows those whatever we do with the
// last component.
fs::path followLinks(const fs::path& destination) {
  fs::path path = destination;
  for (int hops = 0;; ++hops) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0 || !S_ISLNK(st.st_mode) || isProcLink(path)) return path;
    if (hops == kMaxLinkHops) {
      throw OutputError(fmt::format("cannot write {}: {}", destination.string(), errnoText(ELOOP)));
    }
    std::error_code ec;
    const fs::path link = fs::read_symlink(path, ec);
    if (ec)
      throw OutputError(
          fmt::format("cannot write {}: reading the link {}: {}", destination.string(), path.string(), ec.message()));
    path = link.is_absolute() ? link : path.parent_path() / link;
  }
}

PendingOutput::PendingOutput(fs::path destination, Temporary temporary) : destination_(std::move(destination)) {
  if (destination_.empty()) throw OutputError("cannot write to an empty file name");
  target_ = followLinks(destination_);
  struct stat st {};
  if (::lstat(target_.c_str(), &st) == 0) {
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode)) {
      openInPlace(0);
      return;
    }
    if (S_ISFIFO(st.st_mode)) {
      // Opening a FIFO to write waits for a reader, and the wait restarts after a signal whose
      // handler returns (render's SIGINT/SIGTERM): with nobody reading the command would hang for
      // good. O_NONBLOCK makes it fail at once (ENXIO) instead; openInPlace clears it again, so
      // writes to a reader that is there block as writes to any pipe do.
      openInPlace(O_NONBLOCK);
      return;
    }
    if (S_ISLNK(st.st_mode)) {  // a process's open file (followLinks stops only at those)
      // Appended to: a regular file behind it gets our lines after what it holds, not over them.
      // A pipe behind it (`particles … | head`) is a FIFO to open(), refused when nobody reads.
      struct stat behind {};
      const bool pipe = ::stat(target_.c_str(), &behind) == 0 && S_ISFIFO(behind.st_mode);
      openInPlace(O_APPEND | (pipe ? O_NONBLOCK : 0));
      return;
    }
    if (!S_ISREG(st.st_mode)) fail(fmt::format("it is {}", fileKind(st.st_mode)));
  } else if (errno != ENOENT) {
    fail(errnoText(errno));
  }
  if (!target_.has_filename()) fail("a file name cannot end in '/'");
  folder_ = FileDescriptor(::open(folderOf(target_).c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  if (!folder_.valid()) fail(fmt::format("its folder {}: {}", folderOf(target_).string(), errnoText(errno)));
  name_ = target_.filename().string();
  openReplacement(temporary);
}

PendingOutput::PendingOutput(const ConfinedFolder& folder, const fs::path& relative, Temporary temporary)
    : destination_(folder.shown(relative)) {
  target_ = destination_;
  PlacedName placed = folder.place(relative, true, ConfinedFolder::Create::yes);
  target_ = placed.shown;
  if (placed.kind != EntryKind::absent && placed.kind != EntryKind::regular) {
    // A file of the command's own folder is a regular file: a device or FIFO there is refused at
    // once, never written in place (nor waited on), whoever reads it.
    struct stat st {};
    const bool known = ::fstatat(placed.folder.get(), placed.name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
    fail(fmt::format("it is {}; a file of {} is a regular file", known ? fileKind(st.st_mode) : "not a regular file",
                     folder.root().string()));
  }
  folder_ = std::move(placed.folder);
  name_ = std::move(placed.name);
  confined_ = true;
  openReplacement(temporary);
}

void PendingOutput::openReplacement(Temporary temporary) {
  // The stale temporaries of killed runs, listed through this very folder's descriptor.
  const fs::path procFolder = fmt::format("/proc/self/fd/{}", folder_.get());
  removeStalePartials(::access(procFolder.c_str(), F_OK) == 0 ? procFolder : folderOf(target_), name_);
  if (temporary == Temporary::anonymousWherePossible && openAnonymous()) return;
  openNamed();
}

fs::path PendingOutput::reopenableName(const std::string& name) const {
  if (!confined_) return folderOf(target_) / name;
  const fs::path procName = fmt::format("/proc/self/fd/{}/{}", folder_.get(), name);
  if (::access(procName.c_str(), F_OK) == 0) return procName;
  return folderOf(target_) / name;
}

PendingOutput::~PendingOutput() {
  discard();
}

void PendingOutput::openInPlace(int flags) {
  // No O_CREAT, no O_TRUNC: the device or FIFO is used as it is, never made or emptied by us.
  fd_ = ::open(target_.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY | flags);
  if (fd_ < 0 && errno == ENXIO && (flags & O_NONBLOCK)) fail("it is a FIFO and no process is reading it");
  if (fd_ < 0) fail(errnoText(errno));
  if ((flags & O_NONBLOCK) && ::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK) != 0) {
    const int error = errno;
    discard();
    fail("fcntl: " + errnoText(error));
  }
  route_ = Route::inPlace;
  reopenablePath_ = target_;
}

bool PendingOutput::openAnonymous() {
#ifdef O_TMPFILE
  // Mode 0666 is reduced by the umask as for any created file (checked by tests/test_output.cpp).
  const int fd = ::openat(folder_.get(), ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  // Not supported here (EOPNOTSUPP, EISDIR from kernels before 3.11, EINVAL), or any other
  // failure: the named route tries again and reports its own error, which names the real cause.
  if (fd < 0) return false;
  // Libraries reopen the file by this name and commit() links it in through it: without /proc
  // (a bare chroot or container) the anonymous file would have no usable name.
  const fs::path procName = fmt::format("/proc/self/fd/{}", fd);
  if (::access(procName.c_str(), F_OK) != 0) {
    ::close(fd);
    return false;
  }
  fd_ = fd;
  route_ = Route::anonymous;
  reopenablePath_ = procName;
  return true;
#else
  return false;
#endif
}

void PendingOutput::openNamed() {
  // A name can be taken only by a run of the same pid (reused after a killed run) that is still
  // alive: another number then.
  for (int attempt = 0; fd_ < 0; ++attempt) {
    temporary_ = nextPartialPath(name_).string();
    fd_ = ::openat(folder_.get(), temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ < 0 && (errno != EEXIST || attempt == 99)) {
      const int error = errno;
      temporary_.clear();
      fail(errnoText(error));
    }
  }
  route_ = Route::named;
  reopenablePath_ = reopenableName(temporary_);
}

FilePtr PendingOutput::openStream() {
  const int copy = ::fcntl(fd_, F_DUPFD_CLOEXEC, 0);
  if (copy < 0) fail("dup: " + errnoText(errno));
  FilePtr stream(::fdopen(copy, "wb"));
  if (!stream) {
    const int error = errno;
    ::close(copy);
    fail("fdopen: " + errnoText(error));
  }
  return stream;
}

void PendingOutput::linkAnonymous() {
  // linkat cannot replace a file, so the finished file is linked in under a fresh temporary name
  // and renamed over the target from there. This name exists only between the two calls.
  int error = 0;
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::string name = nextPartialPath(name_).string();
    if (::linkat(AT_FDCWD, reopenablePath_.c_str(), folder_.get(), name.c_str(), AT_SYMLINK_FOLLOW) == 0) {
      temporary_ = name;
      return;
    }
    error = errno;
    if (error == EEXIST) continue;
    // /proc was there when the file was opened; should it be gone, the descriptor itself can be
    // linked, which Linux allows only with CAP_DAC_READ_SEARCH.
    if (::linkat(fd_, "", folder_.get(), name.c_str(), AT_EMPTY_PATH) == 0) {
      temporary_ = name;
      return;
    }
    break;
  }
  discard();
  fail(fmt::format("linkat into {}: {}", folderOf(target_).string(), errnoText(error)));
}

void PendingOutput::commit() {
  if (done_) throw std::logic_error("PendingOutput::commit called after commit or discard");
  if (route_ != Route::inPlace) {
    struct stat existing {};
    if (::fstatat(folder_.get(), name_.c_str(), &existing, AT_SYMLINK_NOFOLLOW) == 0) {
      // Checked again: between open and now something else may have taken the name, and a
      // device, FIFO, directory or link there is not ours to replace.
      if (!S_ISREG(existing.st_mode)) {
        discard();
        fail(fmt::format("it has become {} while the output was written, and is left as it is",
                         fileKind(existing.st_mode)));
      }
      // fopen(…, "w") would keep the file's permissions; so does its replacement. Never a
      // set-id bit: those are not carried over to a file we wrote.
      if (::fchmod(fd_, existing.st_mode & 0777) != 0) {
        const int error = errno;
        discard();
        fail("fchmod: " + errnoText(error));
      }
    }
    if (route_ == Route::anonymous) linkAnonymous();
  }
  // Closed before it is published: close is where some filesystems (NFS) report a failed write.
  if (::close(std::exchange(fd_, -1)) != 0) {
    const int error = errno;
    discard();
    fail(errnoText(error));
  }
  if (route_ != Route::inPlace && ::renameat(folder_.get(), temporary_.c_str(), folder_.get(), name_.c_str()) != 0) {
    const std::string reason =
        fmt::format("rename from {}: {}", (folderOf(target_) / temporary_).string(), errnoText(errno));
    discard();
    fail(reason);
  }
  temporary_.clear();
  done_ = true;
}

void PendingOutput::discard() noexcept {
  if (fd_ >= 0) ::close(std::exchange(fd_, -1));
  if (!temporary_.empty()) ::unlinkat(folder_.get(), temporary_.c_str(), 0);
  temporary_.clear();
  done_ = true;
}

void PendingOutput::fail(const std::string& reason) const {
  const std::string name = target_.empty() || target_ == destination_
                               ? destination_.string()
                               : fmt::format("{} (a link to {})", destination_.string(), target_.string());
  throw OutputError(fmt::format("cannot write {}: {}", name, reason));
}

}  // namespace particles::output
