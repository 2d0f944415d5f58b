#pragma once
// Colours of a figure. Series colours are the ten of Tableau 10 (also matplotlib's default
// cycle): distinct from each other on screen and in print; past ten they repeat.

#include <cstddef>

namespace particles::plot {

struct Rgb {
  double r, g, b;  // 0…1
};

Rgb seriesColour(std::size_t index);

inline constexpr Rgb kBackground{1.0, 1.0, 1.0};
inline constexpr Rgb kInk{0.10, 0.10, 0.10};       // text, frame and ticks
inline constexpr Rgb kMutedInk{0.45, 0.45, 0.45};  // "no data", "n/a"
inline constexpr Rgb kGrid{0.90, 0.90, 0.90};      // major grid lines
inline constexpr Rgb kLegendBorder{0.80, 0.80, 0.80};
inline constexpr Rgb kBand{0.99, 0.92, 0.78};     // a shaded interval of x (LineChart::bands)
inline constexpr Rgb kBandInk{0.55, 0.35, 0.05};  // its label

}  // namespace particles::plot
