#pragma once
// Colours as scenarios write them: a CSS named colour ("orange", "steelblue": the 148 names of CSS
// Color Module Level 4, which are also matplotlib's CSS4_COLORS) or #rrggbb / #rrggbbaa in hex,
// either case. Alpha is straight; a name is opaque.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "style/style.hpp"

namespace particles::style {

// The colour `text` names, or nothing for text that is neither a known name (case-insensitive) nor
// # with 6 or 8 hex digits.
std::optional<Color> colorFromText(std::string_view text);
// Every CSS name colorFromText knows, in lower case, sorted (for "did you mean").
const std::vector<std::string>& colorNames();
// #rrggbb, or #rrggbbaa when not opaque: the text colorFromText reads back as the same colour.
std::string hexText(const Color& color);

}  // namespace particles::style
