#pragma once
// Writing references (`particles golden update`, golden/README.md), and merging report folders
// (`particles golden report`). References are written whole or not at all (a temporary name, then
// a rename), and only where the file's bytes change.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "golden/check.hpp"
#include "golden/results.hpp"
#include "scenario/golden_manifest.hpp"

namespace particles::golden {

struct ReferenceChange {
  std::string name;
  enum class Kind { created, changed, unchanged } kind = Kind::unchanged;
  std::string how;   // for a change: by how much ("0.31 % of the pixels differ by more than 16, largest 200")
  std::string from;  // the file it was taken from (--from), or empty
};

struct Refusal {
  std::string name;
  std::string why;
};

struct UpdateOutcome {
  std::vector<ReferenceChange> changes;
  std::vector<Refusal> refused;     // --from: checks whose folders disagree or hold nothing usable
  std::vector<std::string> errors;  // checks that could not be rendered or simulated: `NAME: why`
  std::vector<std::string> notes;   // --from: folders set aside (another manifest, other settings), and why
};

// Where a manifest's references may be read and written: every reference lies beneath
// the references folder once resolved, or OutsideFolderError names it (a link that leads out); and
// for `update` (`written`), none is the same file as the manifest or one of its scenarios
// (output::SameFileError: update would overwrite its own input). Check, update and update --from
// call this before they read a reference, write one or remove anything: both are exit 2.
void requireReferencesInPlace(const scenario::GoldenManifest& manifest, bool written);

// Writes the actual frame or state of every result of `run` (made with keepAll into `folder`) as
// its reference. Controls (`expect: differ`) and checks that compare with another's reference are
// never written. Throws OutputError when a reference cannot be written.
UpdateOutcome writeRenderedReferences(const scenario::GoldenManifest& manifest, const std::filesystem::path& folder,
                                      const CheckRun& run, std::uintmax_t maxInputMiB);

// Accepts the actual frames and states of report folders (`check -o DIR`, downloaded from CI) as
// references, without rendering: every check of `names` (all when empty) that failed or had no
// reference. Folders of another manifest's run, or of a run with settings over the manifest's
// (--raster, --threshold, --max-share), are set aside with a note. A check is refused, and named, when the folders
// disagree on it (one passed, another failed, or their actual files differ), when its file is not a PNG or state file,
// or when the manifest no longer has it. Throws std::invalid_argument for a folder that is not a report (readResults)
// and OutputError when a reference cannot be written.
UpdateOutcome acceptReferences(const scenario::GoldenManifest& manifest,
                               const std::vector<std::filesystem::path>& folders, const std::vector<std::string>& names,
                               std::uintmax_t maxInputMiB);

// Merges the report folders of a run's shards into `into` (which exists, empty): their results in
// one, the kept files copied. Folders are taken in shard order when each names its shard. Throws
// std::invalid_argument when a folder is not a report, two hold the same check, or two kept files
// collide: the same path claimed twice (one would show the other's picture), one file's path a
// folder of another's, or a kept file named as one of the report's pages.
GoldenResults mergeReports(const std::vector<std::filesystem::path>& folders, const std::filesystem::path& into,
                           std::uintmax_t maxInputMiB);

}  // namespace particles::golden
