#pragma once
// The rule for every file a command writes, replaces or removes inside a folder it owns:
// the file lies beneath that folder once resolved. No `..` leaves it, and no symbolic link on the
// way or at the end leads outside it. The golden references folder, a golden report folder, a
// sweep's output folder and the folders a job writes into are such folders.
//
// The rule is checked where the file is written, not on its name beforehand: a ConfinedFolder
// holds its folder open, and every name beneath it is reached from that descriptor one component
// at a time (openat with O_NOFOLLOW). A link is read (readlinkat) and its target walked the same
// way from the folder it sits in: an absolute target, or a `..` above the folder, is refused.
// A `..` is taken by going back to the descriptor already held for the folder above, never by
// opening "..", so a folder moved elsewhere while we walk cannot lead us out. Someone who swaps a
// component for a link between two steps makes the step fail (O_NOFOLLOW), never escape. This is
// what openat2's RESOLVE_BENEATH does in the kernel; the walk here works on every Linux kernel
// and gives the same answers on all of them.
//
// What is refused is bad input, exit code 2: OutsideFolderError. A failure of the system (a full
// disk, no permission) is an OutputError, exit code 3.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace particles::output {

// A file of a command's folder that would lie outside it once resolved: `..` above the folder, an
// absolute path, or a symbolic link that leads outside. The message names the file, the folder and
// the link.
class OutsideFolderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An open file descriptor, closed once.
class FileDescriptor {
 public:
  FileDescriptor() = default;
  explicit FileDescriptor(int fd) : fd_(fd) {}
  ~FileDescriptor() { reset(); }
  FileDescriptor(FileDescriptor&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  FileDescriptor& operator=(FileDescriptor&& other) noexcept {
    if (this != &other) {
      reset();
      fd_ = std::exchange(other.fd_, -1);
    }
    return *this;
  }
  FileDescriptor(const FileDescriptor&) = delete;
  FileDescriptor& operator=(const FileDescriptor&) = delete;

  int get() const { return fd_; }
  bool valid() const { return fd_ >= 0; }
  void reset() noexcept;

 private:
  int fd_ = -1;
};

// What a name beneath a folder is, links at the end followed (beneath the folder) unless asked not to.
enum class EntryKind { absent, regular, directory, symlink, other };

// A name beneath a confined folder, resolved: the folder holding it (open) and its last component.
struct PlacedName {
  FileDescriptor folder;
  std::string name;  // never empty, ".", ".." or with a '/'
  EntryKind kind = EntryKind::absent;
  std::filesystem::path shown;  // root / the path as resolved, for messages
};

class ConfinedFolder {
 public:
  enum class Create { no, yes };
  // Opens `root`. Links in the root's own path are followed: the user named that folder. With
  // Create::yes the root and the folders above it are made when missing. Throws OutputError when
  // it cannot be opened or made, or is not a folder.
  explicit ConfinedFolder(std::filesystem::path root, Create create = Create::no);

  const std::filesystem::path& root() const { return root_; }
  int fd() const { return fd_.get(); }

  // The file `relative` names (relative to the root: an absolute path is refused, so is an empty
  // one), with the folders on its way resolved beneath the root and, where `followLast`, the links
  // at its end too. With Create::yes the folders on the way are made when missing. Throws
  // OutsideFolderError, or OutputError when a folder on the way is missing (Create::no: then the
  // kind is `absent` and `folder` the deepest one found, so check `kind`), a file, or unreadable.
  PlacedName place(const std::filesystem::path& relative, bool followLast, Create create = Create::no) const;

  // What `relative` is, links at its end followed beneath the root; `absent` when it or a folder
  // on its way is missing. Throws OutsideFolderError for a link that leads outside.
  EntryKind kindOf(const std::filesystem::path& relative) const;

  // A folder beneath, opened (O_PATH); made with the folders on its way when `create` says so.
  // Throws OutsideFolderError, or OutputError when it is missing or not a folder.
  FileDescriptor openFolder(const std::filesystem::path& relative, Create create) const;

  // Writes `bytes` to `relative` whole (output::OutputFile: a temporary in the same folder,
  // renamed over the name on success), making the folders on its way. A link at the end that stays
  // beneath is followed: its target is replaced, the link stays. Anything but a regular file or
  // nothing at the end is refused (OutsideFolderError when it leads out, OutputError otherwise).
  void writeFile(const std::filesystem::path& relative, std::string_view bytes) const;

  // Removes the entry `relative` names, never following a link at its end (a link is removed as a
  // link). Missing: nothing to do. A folder must be empty. Returns whether it removed something;
  // throws OutsideFolderError, or OutputError when it cannot.
  bool remove(const std::filesystem::path& relative) const;

  // The path for messages: root / relative.
  std::filesystem::path shown(const std::filesystem::path& relative) const;

 private:
  std::filesystem::path root_;
  FileDescriptor fd_;
};

// Whether `path` lies beneath `folder` by their names alone (both made absolute and lexically
// normal): the relative path from the folder to it, or nullopt-like empty path when it does not.
// For the command lines that name files by absolute paths (a sweep's job rows); the files are
// then reached through ConfinedFolder, which checks the links.
std::filesystem::path relativeBeneath(const std::filesystem::path& path, const std::filesystem::path& folder);

}  // namespace particles::output
