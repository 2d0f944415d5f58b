#pragma once
// The colormaps a style colours by (style/style.hpp's ColormapName): viridis, magma, inferno,
// plasma and cividis as matplotlib's 256-entry tables (style/colormap_tables.cpp, generated from
// matplotlib by scripts/make-colormap-tables and compared with it by a test), coolwarm as
// matplotlib samples Moreland's diverging map into 256 entries, and gray from black to white.
// A value t in [0, 1] takes entry floor(t · 256) (255 at t = 1), as matplotlib's ListedColormap
// with N = 256 does; `_r` reverses the table.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "style/style.hpp"

namespace particles::style {

// Entries per table.
inline constexpr int kColormapEntries = 256;

// A table's entry as matplotlib holds it: red, green and blue in [0, 1].
using ColormapEntry = std::array<float, 3>;

// The 256 entries of `name` (not reversed), as matplotlib gives them.
const std::array<ColormapEntry, kColormapEntries>& colormapTable(ColormapName name);

// The colour at t (clamped to [0, 1]; NaN takes the first entry), each channel rounded to 8 bits
// as matplotlib's to_rgba(…, bytes=True) does (floor(c · 255.999…)? no: round(c · 255)).
Color colormapColor(const Colormap& map, double t);

// "viridis", "magma_r", …: the name scenarios give a colormap, and back.
std::optional<Colormap> colormapFromName(std::string_view name);
std::string nameOf(const Colormap& map);
// Every name colormapFromName takes: the seven maps, then each with `_r`.
std::vector<std::string> colormapNames();

}  // namespace particles::style
