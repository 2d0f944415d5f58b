#pragma once
// results.json (results.hpp): the results for scripts, and what `golden report` merges and
// `golden update --from` accepts. Written here; readResults and summaryLine are results.hpp's.
//
// One object, keys in this order: "format": "particles-golden-results", "version": 1, "counts"
// (passed, failed, missing, error; checked against the results on reading), "runs", "frames",
// "states", each result with every field of its struct under its snake_case name (an absent
// optional is null). Numbers that are not finite (a state's value of a simulation that blew up)
// are the strings "nan", "inf" and "-inf". Strings are valid UTF-8 (report_text.hpp: validUtf8).

#include <string>

#include "golden/results.hpp"

namespace particles::golden::report {

inline constexpr std::string_view kResultsFormat = "particles-golden-results";
inline constexpr int kResultsVersion = 1;

// The deepest nesting of arrays and objects the reader takes, checked before the text is parsed
// (json_reader.hpp: parseJsonText), so that nothing that walks a parsed value recursively can run
// out of stack. A results file nests 5 deep (the file, "frames", a frame, its "numbers", the
// "box"); 64 leaves room for later versions and is orders of magnitude below the 200,000 levels
// that overflowed an 8 MiB stack in dump().
inline constexpr int kMaxResultsDepth = 64;

// The text of results.json, ending in a line break.
std::string resultsJson(const GoldenResults& results);

}  // namespace particles::golden::report
