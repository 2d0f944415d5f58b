#pragma once
// report.html (results.hpp): what people read when CI fails. One self-contained page (inline CSS
// and JavaScript, nothing fetched from a network) linking the pictures and state files beside it
// by their relative paths, so the folder is whole on its own.
//
// Top to bottom: the counts and the facts of each run; the failures first (failed, missing,
// error; frames, then states), each with what it needs to be understood and reproduced: a frame's
// expected, actual and diff pictures side by side (each a link to the full-size file), its numbers
// and commands, a state's first value beyond tolerance and its largest deviation; then the passing
// results as compact tables. Everything is there with JavaScript off; the script only adds, to
// each failing frame with both pictures, a slider (actual over expected, cut where the range says)
// and a blink comparison, which are `hidden` until it runs. The same results give the same bytes.

#include <string>

#include "golden/results.hpp"

namespace particles::golden::report {

// The text of report.html: HTML5 in UTF-8 (report_text.hpp: escapeMarkup, urlPath).
std::string reportHtml(const GoldenResults& results);

}  // namespace particles::golden::report
