#pragma once
// The tables behind style/colormap.hpp, generated from matplotlib into colormap_tables.cpp by
// scripts/make-colormap-tables (which says how and why); for colormap.cpp alone.

#include <array>
#include <cstdint>

#include "style/colormap.hpp"

namespace particles::style {

using ColormapTable = std::array<ColormapEntry, kColormapEntries>;
// A table's entries in 8 bits, as matplotlib's `cmap(i, bytes=True)` gives them.
using ColormapBytes = std::array<std::array<std::uint8_t, 3>, kColormapEntries>;

// matplotlib's 8-bit colours of the reversed map where they are not the forward ones read
// backwards (gray_r: matplotlib samples a reversed LinearSegmentedColormap anew), else nullptr.
const ColormapBytes* matplotlibReversedBytes(ColormapName name);

}  // namespace particles::style
