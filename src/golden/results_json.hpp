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

// The text of results.json, ending in a line break.
std::string resultsJson(const GoldenResults& results);

}  // namespace particles::golden::report
