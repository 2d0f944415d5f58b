#pragma once
// What a frame shows beyond its geometry (docs/scenarios.md, "style"): which quantity colours the
// particles, springs and bodies and through which colormap, a colour bar, a title, a scale bar,
// and the selections that give some particles or bodies their own colour, size, trail, arrow or
// label. Plain data: the scenario loader fills it from a scenario's `style` section (with
// `render --style FILE` and `--set style.…` merged over it) and resolves the selections' names to
// indices; the renderer turns it, frame by frame, into each shape's colour and width
// (render/frame_look.hpp). No YAML, no GL, no files here.

#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace particles::style {

// A colour, 8 bits a channel, alpha straight (not premultiplied): 255 opaque. Scenarios write CSS
// names ("orange") or #rrggbb / #rrggbbaa (style/color.hpp).
struct Color {
  std::uint8_t r = 0, g = 0, b = 0, a = 255;
  bool operator==(const Color&) const = default;
};

// What particles can be coloured by (per particle, at the frame's time).
enum class ParticleQuantity {
  speed,          // |v|, m/s
  velocityX,      // vx, m/s
  velocityY,      // vy, m/s
  acceleration,   // |a| = |F| / m with every force and constraint force, m/s²
  kineticEnergy,  // ½ m |v|², J
  height,         // y, m
  mass,           // kg
};
// What springs can be coloured by (per spring).
enum class SpringQuantity {
  strain,   // |l| / rest − 1: negative compressed, positive stretched
  tension,  // ks (|l| − rest), N: the elastic force along the spring, positive pulling
  energy,   // ½ ks (|l| − rest)², J
};
// What rigid bodies can be coloured by (per body).
enum class BodyQuantity {
  speed,         // |v| of the centre of mass, m/s
  angularSpeed,  // |ω|, rad/s
};

// The colormaps: matplotlib's viridis, magma, inferno, plasma and cividis (its 256-entry tables,
// exactly), coolwarm (Moreland's diverging map, as matplotlib samples it) and gray; each reversed
// by `_r` (style/colormap.hpp).
enum class ColormapName { viridis, magma, inferno, plasma, cividis, coolwarm, gray };
struct Colormap {
  ColormapName name = ColormapName::viridis;
  bool reversed = false;
  bool operator==(const Colormap&) const = default;
};

// The values a colormap spans: below lo the first colour, above hi the last.
struct Range {
  bool automatic = true;  // `auto`: the quantity's range over every frame the output shows
  double lo = 0.0, hi = 1.0;  // when not automatic: finite, lo < hi (and lo > 0 on a log scale)
  bool logScale = false;  // `scale: log`: colours by log10(value); values ≤ 0 take the first colour
  bool operator==(const Range&) const = default;
};

// A length on the frame: in pixels (`3px`) or in metres of the world (`0.02m`, or a bare number).
struct Length {
  double value = 0.0;
  bool pixels = true;
  bool operator==(const Length&) const = default;
};

struct ParticleStyle {
  std::optional<ParticleQuantity> colorBy;  // none: `color`, else the theme's particle colour
  Colormap colormap;                        // viridis
  Range range;
  std::optional<Color> color;               // every particle's colour when colorBy is none
  std::optional<Length> radius;             // none: the render's (--particle-radius, 4 px)
};

struct SpringStyle {
  SpringQuantity colorBy = SpringQuantity::strain;
  // none: the theme's three strain colours (compressed, at rest, stretched) across the range.
  std::optional<Colormap> colormap;
  // Not automatic by default: strain from −0.2 to 0.2 reaches the full colours, as without a style.
  Range range{.automatic = false, .lo = -0.2, .hi = 0.2};
  bool rangeGiven = false;      // whether the scenario gave `range` (else the quantity's default)
  std::optional<Color> color;   // one colour for every spring, instead of colouring by a quantity
  std::optional<Length> width;  // none: 1.5 px
};

struct BodyStyle {
  std::optional<BodyQuantity> colorBy;  // none: `color`, else the theme's body colour
  Colormap colormap;
  Range range;
  std::optional<Color> color;    // the fill
  std::optional<Color> outline;  // none: the theme's outline colour
};

// Which shapes a colour bar explains.
enum class ColorbarSubject { particles, springs, bodies };
enum class ColorbarPosition { right, left, top, bottom };
struct ColorbarStyle {
  // none: the first of particles, springs and bodies coloured by a quantity
  std::optional<ColorbarSubject> subject;
  std::string label;  // with its unit: "speed (m/s)"; empty: the quantity's name and unit
  ColorbarPosition position = ColorbarPosition::right;
};

// A fading line along a selected particle's or body's path.
struct TrailStyle {
  double seconds = std::numeric_limits<double>::infinity();  // how far back; infinity: the whole run
  Length width{2.0, true};
  std::optional<Color> color;  // none: the shape's own colour
};

enum class ArrowQuantity { velocity, force };
struct ArrowStyle {
  ArrowQuantity of = ArrowQuantity::velocity;
  double scale = 0.1;            // metres of arrow per unit of the quantity (m per m/s, m per N)
  Length max{80.0, true};        // the longest arrow drawn; longer ones are capped at it
  std::optional<Color> color;    // none: the theme's arrow colour
};

// Some particles or bodies, named as references name them (docs/physics.md §11: `bob`,
// `cloth[0][*]`, `link2`), given their own look. Later selections win where they overlap.
struct Selection {
  std::string particlesSelector;  // as written, for messages; empty when it selects bodies
  std::string bodiesSelector;
  std::vector<int> particles;  // resolved: particle indices
  std::vector<int> bodies;     // resolved: body indices
  std::optional<Color> color;
  std::optional<Length> radius;  // particles only
  std::optional<TrailStyle> trail;
  std::optional<ArrowStyle> arrow;
  std::string label;  // drawn beside each selected particle or body; printable, bounded
};

// The most characters a label or title holds (longer text is an error).
inline constexpr size_t kMaxLabelLength = 200;

struct Style {
  ParticleStyle particles;
  SpringStyle springs;
  BodyStyle bodies;
  std::optional<ColorbarStyle> colorbar;
  std::string title;
  bool scaleBar = false;
  std::vector<Selection> select;

  // Whether anything differs from a frame without a style (the renderer's fast path).
  bool isPlain() const;
};

// The names scenarios give quantities, colormaps and colour-bar settings, and back; *Names() lists
// every accepted name (for "did you mean" and the JSON Schema), in the order above.
std::optional<ParticleQuantity> particleQuantityFromName(std::string_view name);
std::optional<SpringQuantity> springQuantityFromName(std::string_view name);
std::optional<BodyQuantity> bodyQuantityFromName(std::string_view name);
std::optional<ColorbarSubject> colorbarSubjectFromName(std::string_view name);
std::optional<ColorbarPosition> colorbarPositionFromName(std::string_view name);
std::optional<ArrowQuantity> arrowQuantityFromName(std::string_view name);
std::string_view nameOf(ParticleQuantity q);  // "speed", "velocity_x", "kinetic_energy", …
std::string_view nameOf(SpringQuantity q);
std::string_view nameOf(BodyQuantity q);
std::string_view nameOf(ColorbarSubject s);
std::string_view nameOf(ColorbarPosition p);
std::string_view nameOf(ArrowQuantity q);
std::vector<std::string> particleQuantityNames();
std::vector<std::string> springQuantityNames();
std::vector<std::string> bodyQuantityNames();
std::vector<std::string> colorbarSubjectNames();
std::vector<std::string> colorbarPositionNames();
std::vector<std::string> arrowQuantityNames();
// Each quantity's unit as a colour bar's default label writes it: "m/s", "J", "" (strain).
std::string_view unitOf(ParticleQuantity q);
std::string_view unitOf(SpringQuantity q);
std::string_view unitOf(BodyQuantity q);

}  // namespace particles::style
