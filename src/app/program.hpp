#pragma once
// The program from its command line, for main.cpp: builds the command line (cli.hpp), parses
// `args` (argv without argv[0]) and runs the command it names. Apart from cli.hpp so that main.cpp
// compiles without CLI11's headers (each of its files that includes them took 7–10 s to compile).

#include <string>
#include <vector>

namespace particles::app {

// The exit code: 0 after the help or the version, kBadInput after a usage error (printed, as CLI11
// prints them), else the command's (Cli::dispatch).
int runProgram(const std::vector<std::string>& args);

}  // namespace particles::app
