#pragma once
// The rule: an output is never one of the command's inputs, and no two of its outputs
// are one file. Every command checks its files with requireDistinctFiles before any work starts,
// so a typo or a clever path cannot make `--record` replace `--stats`, `concat -o` a segment it
// joins, or `compare --diff` the frame it compares.
//
// Two paths name the same file when
//  - both exist and are one file: the same device and inode, however the paths get there (`..`,
//    `./`, symbolic links in any component, hard links, /dev/stdout when it is that file);
//  - or one does not exist yet and both resolve to the same name: the last component's symbolic
//    links followed as PendingOutput follows them (a dangling link names its target), then the
//    folder made canonical (std::filesystem::weakly_canonical).
// A character device (/dev/null, a terminal) is exempt: it is written in place and keeps nothing
// that a second writer could overwrite, so `--stats /dev/null --trace /dev/null` is fine.
// An output that is a folder replaced whole (a golden report folder) also replaces everything
// beneath it: an input there, or the folder of an input, is refused as well (both paths made
// canonical as above, then compared component by component).
// Inputs are not checked against each other (`concat a.mp4 a.mp4` joins a video to itself).

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace particles::output {

// A path as the command line names it, for messages: {"--record", "r.txt"}, {"segment", "a0.mp4"}.
// An empty path (an option not given) is skipped.
struct NamedFile {
  std::string role;
  std::filesystem::path path;
  // An output that is a folder the command replaces whole, with all it holds; ignored for an input.
  bool wholeFolder = false;
};

// Two of a command's files are one: bad usage, which the program maps to exit code 2 (not an
// OutputError, exit 3: nothing failed to be written, the command was refused before it began).
class SameFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws SameFileError naming both paths when an output is the same file as another output or as
// an input, or is a folder replaced whole that holds an input, by the rule above.
void requireDistinctFiles(const std::vector<NamedFile>& outputs, const std::vector<NamedFile>& inputs = {});

// Whether `a` and `b` name the same file by the rule above.
bool sameFile(const std::filesystem::path& a, const std::filesystem::path& b);

}  // namespace particles::output
