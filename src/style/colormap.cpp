#include "style/colormap.hpp"

#include <cmath>
#include <cstdint>

#include "style/colormap_tables.hpp"

namespace particles::style {

namespace {

// The names in ColormapName's order.
constexpr std::array<std::string_view, 7> kColormapNames = {"viridis", "magma",    "inferno", "plasma",
                                                            "cividis", "coolwarm", "gray"};
constexpr std::string_view kReversedSuffix = "_r";

// The entry matplotlib's Colormap.__call__ takes for a float t with N = 256 (matplotlib/colors.py,
// 3.6): xa = t · N in float64 (exact: N is a power of two), negative → under (the first entry),
// xa == N → N − 1, clipped to [−1, N] and truncated by astype(int), above N − 1 → over (the last).
// NaN is not a number here; colormapColor handles it first.
int colormapIndex(double t) {
  const double scaled = t * kColormapEntries;
  if (scaled < 0.0) return 0;
  if (scaled >= kColormapEntries - 1) return kColormapEntries - 1;
  return static_cast<int>(scaled);  // truncation toward zero, as numpy's astype(int)
}

// matplotlib's bytes=True: `(lut * 255).astype(np.uint8)`, the product in float64, rounded toward
// zero (an entry is in [0, 1], so the product is in [0, 255] and the cast is defined).
std::uint8_t toByte(double channel) {
  return static_cast<std::uint8_t>(channel * 255.0);
}

}  // namespace

Color colormapColor(const Colormap& map, double t) {
  const int index = std::isnan(t) ? 0 : colormapIndex(t);
  if (map.reversed) {
    if (const ColormapBytes* bytes = matplotlibReversedBytes(map.name)) {
      const auto& rgb = (*bytes)[index];
      return Color{rgb[0], rgb[1], rgb[2], 255};
    }
  }
  const ColormapEntry& entry = colormapTable(map.name)[map.reversed ? kColormapEntries - 1 - index : index];
  return Color{toByte(entry[0]), toByte(entry[1]), toByte(entry[2]), 255};
}

std::optional<Colormap> colormapFromName(std::string_view name) {
  const bool reversed = name.ends_with(kReversedSuffix);
  if (reversed) name.remove_suffix(kReversedSuffix.size());
  for (std::size_t i = 0; i < kColormapNames.size(); ++i) {
    if (kColormapNames[i] == name) return Colormap{static_cast<ColormapName>(i), reversed};
  }
  return std::nullopt;
}

std::string nameOf(const Colormap& map) {
  std::string name(kColormapNames[static_cast<std::size_t>(map.name)]);
  if (map.reversed) name += kReversedSuffix;
  return name;
}

std::vector<std::string> colormapNames() {
  std::vector<std::string> names;
  for (const bool reversed : {false, true}) {
    for (std::size_t i = 0; i < kColormapNames.size(); ++i) {
      names.push_back(nameOf(Colormap{static_cast<ColormapName>(i), reversed}));
    }
  }
  return names;
}

}  // namespace particles::style
