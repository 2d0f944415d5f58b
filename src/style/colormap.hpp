#pragma once
// The colormaps a style colours by (style/style.hpp's ColormapName): viridis, magma, inferno,
// plasma and cividis as matplotlib's 256-entry tables (style/colormap_tables.cpp, generated from
// matplotlib by scripts/make-colormap-tables and compared with it by a test), coolwarm as
// matplotlib samples Moreland's diverging map into 256 entries, and gray from black to white.
// A value t takes entry floor(t · 256) computed in double, 0 below 0 and 255 from t = 1 up, as
// matplotlib's Colormap.__call__ does with N = 256 (`xa = x * N`, `xa[xa == N] = N - 1`, clipped,
// `astype(int)`; matplotlib/colors.py, 3.6); `_r` reads the table backwards, as matplotlib's
// reversed ListedColormap does. Where matplotlib's reversed map is not its table read backwards in
// 8 bits (gray_r: it samples a LinearSegmentedColormap's reversed segments anew, and 1 − x rounds
// otherwise than x), colormapColor gives matplotlib's 8-bit colours of the reversed map.

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "style/style.hpp"

namespace particles::style {

// Entries per table.
inline constexpr int kColormapEntries = 256;

// A table's entry as matplotlib holds it: red, green and blue in [0, 1], the same float64 numbers
// (matplotlib keeps its tables as float64 arrays; float32 would change the 8-bit colours of gray).
using ColormapEntry = std::array<double, 3>;

// The 256 entries of `name` (not reversed), as matplotlib gives them.
const std::array<ColormapEntry, kColormapEntries>& colormapTable(ColormapName name);

// The colour at t, as matplotlib's `colormaps[nameOf(map)](t, bytes=True)`: t below 0 (or −∞)
// takes the first entry, above 1 (or +∞) the last; NaN, matplotlib's "bad" value (transparent
// black there), takes the first entry here, as a value below the range does. Each channel is
// truncated to 8 bits, c · 255 rounded toward zero, as matplotlib's `(lut * 255).astype(np.uint8)`
// does (so 0.5 gives 127, and gray's entry 33, 33/255 in float64, gives 32); alpha is 255.
Color colormapColor(const Colormap& map, double t);

// "viridis", "magma_r", …: the name scenarios give a colormap, and back.
std::optional<Colormap> colormapFromName(std::string_view name);
std::string nameOf(const Colormap& map);
// Every name colormapFromName takes: the seven maps, then each with `_r`.
std::vector<std::string> colormapNames();

}  // namespace particles::style
