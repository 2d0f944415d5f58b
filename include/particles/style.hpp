#pragma once
/// @file
/// A scenario's `style` (docs/scenarios.md, "Style") as a C++ value: what a frame shows beyond its
/// geometry. It mirrors the YAML section key for key, a field's name the camelCase of the key
/// (`color_by` → `colorBy`), and writes names, colours and lengths as strings exactly as YAML does
/// ("speed", "viridis_r", "#4682b4", "3px"). Scenario::setStyle() merges it over the scenario's own
/// section, as `particles render --style FILE` merges a style file, and checks it with the file's
/// checks and messages.
///
/// @code
/// particles::Style look;
/// look.particles = {.colorBy = "speed", .colormap = "magma", .range = particles::ColorRange{.min = 0, .max = 2}};
/// look.colorbar = particles::ColorbarStyle{.label = "speed (m/s)"};
/// look.select = {{.particles = {"cloth[24][12]"}, .trail = particles::TrailStyle{.seconds = 2}, .label = "corner"}};
/// scenario.setStyle(look);
/// @endcode
///
/// Every field is optional: what is left out keeps the scenario's value (or the default). A field
/// cannot say null (YAML's `~`), which takes a scenario's key away: Scenario::setStyle(yaml) can.

#include <optional>
#include <string>
#include <vector>

#include <particles/export.hpp>

namespace particles {

/// Whether a colormap spans its values linearly or by their log₁₀ (`scale` of a range).
enum class RangeScale {
  linear,  ///< the default
  log,     ///< coloured by log₁₀ of the value; values ≤ 0 take the first colour
};

/// The values a colormap spans (docs/scenarios.md, "Ranges"): below the first colour, above the
/// last. Written as YAML: `auto` (neither bound, linear: the default), else the map
/// `{min, max, scale}`. min and max are given both or neither (neither: automatic, the quantity's
/// range over the frames drawn), min < max, and min > 0 on a log scale.
struct ColorRange {
  std::optional<double> min{};            ///< the value at the first colour
  std::optional<double> max{};            ///< the value at the last colour
  RangeScale scale = RangeScale::linear;  ///< linear or log

  bool operator==(const ColorRange&) const = default;  ///< the same range, field by field
};

/// How the particles look: `style.particles`.
struct ParticleStyle {
  /// The quantity that colours them: speed, velocity_x, velocity_y, acceleration, kinetic_energy,
  /// height, mass. Not with color.
  std::optional<std::string> colorBy{};
  std::optional<std::string> colormap{};  ///< viridis, magma, inferno, plasma, cividis, coolwarm, gray; `_r` reversed
  std::optional<ColorRange> range{};      ///< what the colormap spans; automatic by default
  std::optional<std::string> radius{};    ///< a length: "3px", "0.02m" or "0.02" (metres)
  std::optional<std::string> color{};     ///< every particle's colour: a CSS name or "#rrggbb[aa]"

  bool operator==(const ParticleStyle&) const = default;  ///< the same look, field by field
};

/// How the springs look: `style.springs`.
struct SpringStyle {
  std::optional<std::string> colorBy{};   ///< strain (the default), tension, energy. Not with color
  std::optional<std::string> colormap{};  ///< none: the theme's three strain colours
  std::optional<ColorRange> range{};      ///< none: [-0.2, 0.2], the strain's
  std::optional<std::string> width{};     ///< a length; none: 1.5px
  std::optional<std::string> color{};     ///< one colour for every spring instead of a quantity's

  bool operator==(const SpringStyle&) const = default;  ///< the same look, field by field
};

/// How the rigid bodies look: `style.bodies`.
struct BodyStyle {
  std::optional<std::string> color{};     ///< the fill. Not with colorBy
  std::optional<std::string> outline{};   ///< the outline's colour
  std::optional<std::string> colorBy{};   ///< speed (of the centre of mass), angular_speed
  std::optional<std::string> colormap{};  ///< as ParticleStyle::colormap
  std::optional<ColorRange> range{};      ///< what the colormap spans; automatic by default

  bool operator==(const BodyStyle&) const = default;  ///< the same look, field by field
};

/// A colour bar: `style.colorbar`, written as the map `{for, label, position}`, or as `true` (a
/// colour bar with the defaults) or `false` (none) where show says so.
struct ColorbarStyle {
  bool show = true;  ///< false: `colorbar: false`, no colour bar (the other fields are not written)
  /// The key `for` (a C++ keyword): particles, springs or bodies, a class the scene has, coloured
  /// by a quantity; none: the first of them coloured by one.
  std::optional<std::string> for_{};
  std::optional<std::string> label{};     ///< none: the quantity's name and unit
  std::optional<std::string> position{};  ///< right (the default), left, top, bottom

  bool operator==(const ColorbarStyle&) const = default;  ///< the same colour bar, field by field
};

/// A fading line along a selected shape's path: a selection's `trail`.
struct TrailStyle {
  /// How far back, s (> 0); none or infinity: `all`, the whole run.
  std::optional<double> seconds{};
  std::optional<std::string> width{};  ///< a length; none: 2px
  std::optional<std::string> color{};  ///< none: the shape's own colour

  bool operator==(const TrailStyle&) const = default;  ///< the same trail, field by field
};

/// An arrow on each selected shape: a selection's `arrow`, written as the map `{of, scale, max, color}`.
struct ArrowStyle {
  std::optional<std::string> of{};     ///< velocity (the default) or force
  std::optional<double> scale{};       ///< metres of arrow per unit (m per m/s, m per N), > 0; none: 0.1
  std::optional<std::string> max{};    ///< a length, the longest arrow drawn; none: 80px
  std::optional<std::string> color{};  ///< none: the theme's arrow colour

  bool operator==(const ArrowStyle&) const = default;  ///< the same arrow, field by field
};

/// Some particles or rigid bodies given their own look: an entry of `style.select`. Later entries
/// win where they overlap.
struct StyleSelection {
  /// References to particles, as forces name them: "bob", "cloth[24][12]", "cloth[0][*]", a whole
  /// grid "cloth", "#7" (one is written as a reference, several as a list). Not with bodies.
  std::vector<std::string> particles{};
  std::vector<std::string> bodies{};    ///< rigid bodies by name ("link3"); not with particles
  std::optional<std::string> color{};   ///< a CSS name or "#rrggbb[aa]"
  std::optional<std::string> radius{};  ///< a length; particles only
  std::optional<TrailStyle> trail{};    ///< a fading line along the path
  std::optional<ArrowStyle> arrow{};    ///< an arrow of their velocity or force
  std::optional<std::string> label{};   ///< drawn beside each selected shape: one line, ≤ 200 characters

  bool operator==(const StyleSelection&) const = default;  ///< the same selection, field by field
};

/// A scenario's `style` section as a value: Scenario::setStyle() merges it over the scenario's own,
/// key by key, as a style file is merged (maps merged; title, scale_bar and select replaced).
struct Style {
  ParticleStyle particles{};                ///< written when any of its fields is given
  SpringStyle springs{};                    ///< written when any of its fields is given
  BodyStyle bodies{};                       ///< written when any of its fields is given
  std::optional<ColorbarStyle> colorbar{};  ///< a colour bar, or (show = false) none
  std::optional<std::string> title{};       ///< the frame's title: one line, ≤ 200 characters
  std::optional<bool> scaleBar{};           ///< a scale bar, in metres
  std::vector<StyleSelection> select{};     ///< written when not empty: it replaces the scenario's selections

  bool operator==(const Style&) const = default;  ///< the same style, field by field
};

}  // namespace particles
