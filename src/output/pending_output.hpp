#pragma once
// One output file that appears whole or not at all, and never clobbers what is not ours.
//
// What the destination is decides how it is written:
//  - absent or a regular file: a temporary is written and, on commit(), renamed over the
//    destination, so a reader never sees a half-written file and an existing output is replaced
//    only on success. Where the filesystem allows (Linux O_TMPFILE, and /proc for its name) the
//    temporary is anonymous: it has no name in the folder until commit() links it in, so even a
//    run killed outright (SIGKILL) leaves nothing behind. Elsewhere it is named
//    "<destination>.partial-<pid>-<n>" (partial_names.hpp); such names left by killed runs are
//    removed by the next output of the same name into that folder.
//  - a character or block device or a FIFO (/dev/null, a terminal, a named pipe): written in
//    place, opened as it is. Nothing is replaced or removed, on success or failure. A FIFO that no
//    process is reading is refused at once (OutputError) rather than waited on: a command must
//    never hang in open(), where no signal handler of ours can stop it.
//  - a process's open file, a link in /proc (/dev/stdout, /dev/fd/N): written in place too, and
//    appended to, so stdout redirected to a file keeps what was printed before.
//  - a directory or a socket (or any other kind of file): refused with OutputError naming it.
//  - a symbolic link (a chain of them, or a dangling one): the file at its end is what is written,
//    by the rules above, and the link stays a link. The temporary lives in the target's folder, so
//    the rename stays within one filesystem and is atomic.
// A replaced file keeps its permission bits, and a new one gets 0666 less the umask: what
// fopen(…, "w") gives.

#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include "output/confined_folder.hpp"

namespace particles::output {

struct FileCloser {
  void operator()(std::FILE* file) const { std::fclose(file); }
};
using FilePtr = std::unique_ptr<std::FILE, FileCloser>;

// The file a write to `destination` lands in: symbolic links in its last component followed, as
// open(2) follows them, so that the link's target gets the content and the link itself stays (a
// relative link is relative to the folder holding it). Stops at a link in /proc (/dev/stdout: a
// process's open file, not a name), which is returned as it is. Throws OutputError for a loop.
std::filesystem::path followLinks(const std::filesystem::path& destination);

class PendingOutput {
 public:
  enum class Temporary {
    anonymousWherePossible,  // O_TMPFILE, falling back to a named temporary
    named,                   // always "<destination>.partial-<pid>-<n>" (tests of the fallback)
  };
  enum class Route { anonymous, named, inPlace };

  // Opens the file to write (see above). Never waits: a FIFO without a reader is refused. Throws
  // OutputError naming the destination and the reason.
  explicit PendingOutput(std::filesystem::path destination, Temporary temporary = Temporary::anonymousWherePossible);
  // A file of a folder the command owns (confined_folder.hpp): `relative` is reached from the
  // folder's descriptor, the folders on its way made when missing; a link at its end is followed
  // only while it stays beneath the folder (OutsideFolderError otherwise, exit 2), and only a
  // regular file or nothing may be there (no device, FIFO or folder: OutputError). The temporary
  // is made in the folder that holds the file and renamed over it from that folder's descriptor,
  // so a folder swapped for a link meanwhile cannot send the file elsewhere.
  PendingOutput(const ConfinedFolder& folder, const std::filesystem::path& relative,
                Temporary temporary = Temporary::anonymousWherePossible);
  ~PendingOutput();  // discard() unless committed
  PendingOutput(const PendingOutput&) = delete;
  PendingOutput& operator=(const PendingOutput&) = delete;

  // As the caller named it; messages use it.
  const std::filesystem::path& destination() const { return destination_; }
  // The file that is written: the destination with symbolic links followed.
  const std::filesystem::path& target() const { return target_; }
  Route route() const { return route_; }

  // The open file, write-only, owned here: write to it, do not close it.
  int fd() const { return fd_; }
  // A stdio stream over a duplicate of fd(). The caller closes it (and checks fclose, where a
  // full disk shows) before commit().
  FilePtr openStream();
  // A name under which the file being written can be opened again, for libraries that insist on a
  // name (libav, whose mp4 muxer also reopens it for reading to move the index to the front):
  // "/proc/self/fd/<fd>" for an anonymous file, else the named temporary or the device itself.
  const std::filesystem::path& reopenablePath() const { return reopenablePath_; }

  // Publishes the file: renames the temporary over the target, atomically replacing a regular
  // file there; for a device or FIFO only closes it. Throws OutputError (and discards).
  void commit();
  // Drops what was written: an anonymous temporary vanishes with its descriptor, a named one is
  // removed; a device or FIFO is only closed. Never throws; idempotent.
  void discard() noexcept;

 private:
  void openInPlace(int flags);
  void openReplacement(Temporary temporary);
  bool openAnonymous();
  void openNamed();
  void linkAnonymous();
  // A name in folder_ under which the temporary can be opened again: through /proc where it is
  // there, so that the name reaches this very folder (confined), else beside the target.
  std::filesystem::path reopenableName(const std::string& name) const;
  [[noreturn]] void fail(const std::string& reason) const;

  std::filesystem::path destination_, target_;
  FileDescriptor folder_;  // the folder holding target_ (not for the in-place route)
  std::string name_;       // target_'s last component, in folder_
  std::string temporary_;  // the temporary's name in folder_ while it has one (removed by discard)
  bool confined_ = false;  // made from a ConfinedFolder: names reach folder_ only through its descriptor
  std::filesystem::path reopenablePath_;
  Route route_ = Route::named;
  int fd_ = -1;
  bool done_ = false;
};

}  // namespace particles::output
