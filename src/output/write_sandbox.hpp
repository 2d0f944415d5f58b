#pragma once
// The kernel's own guard for a process that must write only beneath one folder (`particles job`,
// whose folder anyone may have touched: docs/sweeps.md). The job checks every file its row names
// before it runs (output/confined_folder.hpp); this makes the kernel refuse any other write for
// the rest of the process's life, so that a folder swapped for a link while the job runs, or a
// file that a library opens by name, still cannot land outside. It uses Landlock (Linux 5.13 and
// later, where the kernel enables it): writing, making, removing, renaming and truncating files
// are allowed beneath `folder`, and opening devices for writing beneath /dev (a GPU's render
// node, /dev/null), and nowhere else. Reading is not restricted. Already open files (the terminal,
// a Slurm task's log) are not affected.

#include <filesystem>

namespace particles::output {

// Whether the kernel now enforces the rule: false where it has no Landlock (then the checks before
// the run are what stands). Throws OutputError when the folder cannot be opened or the kernel
// refuses a rule it says it supports.
bool restrictWritesBeneath(const std::filesystem::path& folder);

}  // namespace particles::output
