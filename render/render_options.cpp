#include "render/render_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace particles::render {

namespace {

constexpr std::array<ThemeName, 2> kThemes = {ThemeName::dark, ThemeName::light};                  // as kThemeNames
constexpr std::array<Raster, 3> kRasters = {Raster::automatic, Raster::triangles, Raster::tiles};  // as kRasterNames

}  // namespace

std::optional<ThemeName> themeFromName(std::string_view name) {
  for (size_t i = 0; i < kThemes.size(); ++i) {
    if (kThemeNames[i] == name) return kThemes[i];
  }
  return std::nullopt;
}

std::optional<Raster> rasterFromName(std::string_view name) {
  for (size_t i = 0; i < kRasters.size(); ++i) {
    if (kRasterNames[i] == name) return kRasters[i];
  }
  return std::nullopt;
}

std::string_view themeNameOf(ThemeName theme) {
  return kThemeNames[size_t(std::find(kThemes.begin(), kThemes.end(), theme) - kThemes.begin())];
}

std::string_view rasterNameOf(Raster raster) {
  return kRasterNames[size_t(std::find(kRasters.begin(), kRasters.end(), raster) - kRasters.begin())];
}

void validate(const RenderOptions& o) {
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide) {
    throw std::invalid_argument(fmt::format("image size {}x{} is out of range (1 to {} pixels per side)", o.width,
                                            o.height, kMaxImageSide));
  }
  if (std::find(kSampleCounts.begin(), kSampleCounts.end(), o.msaa) == kSampleCounts.end()) {
    throw std::invalid_argument(fmt::format("msaa {} is not one of {}", o.msaa, sampleCountsText()));
  }
  if (!(o.particleRadius.value > 0.0)) throw std::invalid_argument("particle radius must be positive");
  if (!(o.springWidthPx > 0.0) || !(o.rodWidthPx > 0.0) || !(o.guideWidthPx > 0.0) || !(o.outlineWidthPx > 0.0)) {
    throw std::invalid_argument("line widths must be positive");
  }
  if (!(o.strainForFullColor > 0.0)) throw std::invalid_argument("strainForFullColor must be positive");
}

std::string sampleCountsText() {
  std::vector<std::string> counts;
  for (int n : kSampleCounts) counts.push_back(n == 1 ? "1 (off)" : std::to_string(n));
  const std::string last = counts.back();
  counts.pop_back();
  return fmt::format("{} or {}", fmt::join(counts, ", "), last);
}

}  // namespace particles::render
