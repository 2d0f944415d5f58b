#include "render/render_options.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/name_table.hpp"

namespace particles::render {

namespace {

constexpr NameTableRow<ThemeName> kThemeNames[] = {{ThemeName::dark, "dark"}, {ThemeName::light, "light"}};
constexpr NameTableRow<Raster> kRasterNames[] = {
    {Raster::automatic, "auto"},
    {Raster::triangles, "triangles"},
    {Raster::tiles, "tiles"},
    {Raster::resident, "resident"},
    {Raster::cpu, "cpu"}};
// RenderOptions::transparentBackground's two values: the theme's colour, or none.
constexpr NameTableRow<bool> kBackgroundNames[] = {{false, "theme"}, {true, "transparent"}};

template <typename Value, std::size_t N>
std::vector<std::string> namesOf(const NameTableRow<Value> (&table)[N]) {
  std::vector<std::string> names;
  for (const auto& [value, name] : table) names.emplace_back(name);
  return names;
}

// "dark or light", "auto, triangles, tiles": the names as the messages list them.
template <typename Value, std::size_t N>
std::string listOf(const NameTableRow<Value> (&table)[N], std::string_view separator) {
  return fmt::format("{}", fmt::join(namesOf(table), separator));
}

// WIDTHxHEIGHT (or WIDTHXHEIGHT), both positive; the range is validate's to check.
bool readSize(std::string_view text, RenderOptions& look) {
  const std::string terminated(text);
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(terminated.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w <= 0 ||
      h <= 0) {
    return false;
  }
  look.width = w;
  look.height = h;
  return true;
}

bool readSampleCount(std::string_view text, RenderOptions& look) {
  int n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  if (error != std::errc() || end != text.data() + text.size() ||
      std::find(kSampleCounts.begin(), kSampleCounts.end(), n) == kSampleCounts.end()) {
    return false;
  }
  look.msaa = n;
  return true;
}

// "4px" (pixels, also a bare number) or "0.02m" (world units), positive.
bool readParticleRadius(std::string_view text, RenderOptions& look) {
  try {
    const std::string terminated(text);
    size_t used = 0;
    const double value = std::stod(terminated, &used);
    const std::string unit = terminated.substr(used);
    if (!(value > 0)) return false;
    if (unit.empty() || unit == "px") {
      look.particleRadius = {value, Length::Unit::pixels};
      return true;
    }
    if (unit == "m") {
      look.particleRadius = {value, Length::Unit::world};
      return true;
    }
  } catch (const std::exception&) {
  }
  return false;
}

// A row whose text is a name of `table`, held in RenderOptions' member `field`: read, and written
// always or only off the program's default.
template <auto field, const auto& table>
bool readNamed(std::string_view text, RenderOptions& look) {
  const auto value = valueNamed(table, text);
  if (value) look.*field = *value;
  return value.has_value();
}

template <auto field, const auto& table, bool always>
std::optional<std::string> writeNamed(const RenderOptions& look) {
  if (!always && look.*field == RenderOptions{}.*field) return std::nullopt;
  return std::string(nameOf(table, look.*field, "?"));
}

std::vector<LookOption> makeLookOptions() {
  return {
      {"--size", "WIDTHxHEIGHT in pixels, e.g. 1280x720", readSize,
       [](const RenderOptions& look) -> std::optional<std::string> {
         return fmt::format("{}x{}", look.width, look.height);
       }},
      {"--msaa", sampleCountsText(), readSampleCount,
       [](const RenderOptions& look) -> std::optional<std::string> { return fmt::format("{}", look.msaa); }},
      {"--theme", listOf(kThemeNames, " or "), readNamed<&RenderOptions::themeName, kThemeNames>,
       writeNamed<&RenderOptions::themeName, kThemeNames, true>},
      {"--background", listOf(kBackgroundNames, " or "),
       readNamed<&RenderOptions::transparentBackground, kBackgroundNames>,
       writeNamed<&RenderOptions::transparentBackground, kBackgroundNames, false>},
      {"--raster", listOf(kRasterNames, ", "), readNamed<&RenderOptions::raster, kRasterNames>,
       writeNamed<&RenderOptions::raster, kRasterNames, false>},
      {"--particle-radius", "a positive length like 4px or 0.02m", readParticleRadius,
       [](const RenderOptions& look) -> std::optional<std::string> {
         const Length radius = look.particleRadius, byDefault = RenderOptions{}.particleRadius;
         if (radius.value == byDefault.value && radius.unit == byDefault.unit) return std::nullopt;
         return fmt::format("{}{}", radius.value, radius.unit == Length::Unit::pixels ? "px" : "m");
       }},
  };
}

}  // namespace

std::optional<ThemeName> themeFromName(std::string_view name) {
  return valueNamed(kThemeNames, name);
}

std::optional<Raster> rasterFromName(std::string_view name) {
  return valueNamed(kRasterNames, name);
}

std::string_view themeNameOf(ThemeName theme) {
  return nameOf(kThemeNames, theme, "?");
}

std::string_view rasterNameOf(Raster raster) {
  return nameOf(kRasterNames, raster, "?");
}

Raster rasterTaken(Raster raster, bool gpu) {
  if (raster != Raster::automatic) return raster;
  return gpu ? Raster::resident : Raster::cpu;
}

std::vector<std::string> rasterNames() {
  return namesOf(kRasterNames);
}

const std::vector<LookOption>& lookOptions() {
  static const std::vector<LookOption> rows = makeLookOptions();
  return rows;
}

const LookOption& lookOption(std::string_view flag) {
  for (const LookOption& row : lookOptions()) {
    if (row.flag == flag) return row;
  }
  throw std::invalid_argument(fmt::format("{} is not a look option", flag));
}

std::vector<std::string> lookWords(const RenderOptions& look) {
  std::vector<std::string> words;
  for (const LookOption& row : lookOptions()) {
    if (std::optional<std::string> text = row.write(look)) {
      words.emplace_back(row.flag);
      words.push_back(std::move(*text));
    }
  }
  return words;
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
