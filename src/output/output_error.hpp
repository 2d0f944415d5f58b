#pragma once
// The error of writing: a file could not be opened, written or renamed into place. The message
// names the path and the failing call with the system's (or the library's) own words. The program
// maps it to exit code 3 ("output failure"). (The room's other error, SameFileError in
// distinct_files.hpp, refuses a command's files before anything is written: exit 2.) It is the
// public particles::OutputError (include/particles/errors.hpp).

#include <particles/errors.hpp>

namespace particles::output {

using OutputError = particles::OutputError;

}  // namespace particles::output
