#!/usr/bin/env bash
# A compiler launcher (CMAKE_CXX_COMPILER_LAUNCHER) for a tree that is only checked for warnings:
# scripts/test's Debug tree, build-debug/. Runs the compile command CMake gives with -fsyntax-only
# appended, which parses, instantiates every template and reports every front-end warning (the
# ones a -O0 build gives: its optimiser-based warnings need -O1 and up, and build/ has those at -O3)
# without generating code, then leaves an empty object file where the command would have written
# one, so that the build tool sees the step done and a rerun skips it. The arguments are passed
# through as they are: nothing here is parsed by a shell.
set -euo pipefail
object=""
args=("$@")
for ((i = 0; i + 1 < ${#args[@]}; i++)); do
  if [ "${args[i]}" = "-o" ]; then object=${args[i + 1]}; fi
done
"$@" -fsyntax-only
if [ -n "$object" ]; then : >"$object"; fi
