#pragma once
// Names of the temporaries the output room leaves on disk: "<name>.partial-<pid>-<n>", beside the
// file or directory <name> they will become (or, for a PNG sequence, be moved into). pid is the
// writing process, n counts within it, so two processes or two outputs never share a name.
//
// Such a name exists only while a named temporary is being written (the fallback where a
// filesystem or a missing /proc rules out an anonymous O_TMPFILE file, the staging directory of a
// PNG sequence) or, for an instant, while an anonymous file is published. A run killed outright
// (SIGKILL, power loss) leaves it behind; the next output of the same name into the same folder
// removes it (removeStalePartials).

#include <filesystem>
#include <string>

namespace particles::output {

// "<beside>.partial-<pid>-<n>" with this process's pid and its next n.
std::filesystem::path nextPartialPath(const std::filesystem::path& beside);

// Removes from `directory` the temporaries that runs writing `name` there left behind when they
// were killed: entries named exactly "<name>.partial-<pid>-<n>" (pid and n decimal digits) that are
// a regular file or a directory (not a link), owned by this user, whose pid is no running process
// (kill(pid, 0) fails with ESRCH). Nothing else is touched: not another output's temporaries,
// not a name that only looks alike ("<name>.partial-abc"), not a live or foreign run's file.
//
// Only `name`'s own temporaries, not every "*.partial-*": the user asked to write `name`, so its
// leftovers are ours to replace, while another name's could belong to a program that happens to
// use the same pattern, and would be swept as a side effect of writing something else.
//
// A pid is looked up in this process's PID namespace: a run in another container writing into a
// shared folder is not seen, and its temporaries of the same name would count as stale.
// Best effort: a failure to list or remove is ignored; returns how many entries were removed.
int removeStalePartials(const std::filesystem::path& directory, const std::string& name) noexcept;

}  // namespace particles::output
