#pragma once
// One word for bash whatever its bytes: the commands a program writes for people to read and copy
// (a sweep's job lists, a golden report's commands that reproduce a failure). The program never
// hands them to a shell.

#include <string>
#include <vector>

namespace particles::output {

// As it is, in '…', or in $'…' when it holds control characters. The one quoting function of the
// program (app/job_record.hpp's splitCommandText reads its forms back).
std::string shellQuote(const std::string& arg);

// A byte bash takes as part of a plain word, quoted or not.
bool isPlainShellChar(char c);

// The words as one command line, each through shellQuote, separated by spaces.
std::string shellCommand(const std::vector<std::string>& words);

}  // namespace particles::output
