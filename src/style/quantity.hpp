#pragma once
// The values a style colours shapes by (style/style.hpp's quantities), read from a frame's Drawing
// (core/drawing.hpp, with the DrawDetail the style asks for), the range they span over the frames
// an output shows, and where a value falls on a colormap.
//
// `range: auto` is the range over every frame the output shows: the whole render's frames, which a
// split render (--frames A:B) finds by the same pass over the same frames as the whole render, so
// that both colour a frame alike (render/video/render_simulation.cpp).

#include <limits>
#include <vector>

#include "core/drawing.hpp"
#include "style/style.hpp"

namespace particles::style {

// What System::draw must add to a frame's Drawing for `style`: velocities for speeds, kinetic
// energy, velocity arrows and trails' nothing; masses for mass and kinetic energy; accelerations for
// acceleration and force arrows.
DrawDetail drawDetailFor(const Style& style);

// Each particle's, spring's (by position, then by index) or body's value of the quantity, into
// `out` (resized). The drawing must carry what drawDetailFor asked for; std::invalid_argument
// otherwise.
void particleValues(const Drawing& frame, ParticleQuantity quantity, std::vector<double>& out);
void springValues(const Drawing& frame, SpringQuantity quantity, std::vector<double>& out);
void bodyValues(const Drawing& frame, BodyQuantity quantity, std::vector<double>& out);

// The smallest and largest finite values seen (on a log scale, of the positive ones only).
struct ValueRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  bool empty() const { return !(lo <= hi); }
  void add(const std::vector<double>& values, bool positiveOnly);
  void add(const ValueRange& other);
};

// Where a value lies between a range's ends, as a colormap's t in [0, 1] (clamped; a value a log
// scale cannot place, ≤ 0 or NaN, is 0).
struct ColorScale {
  double lo = 0.0, hi = 1.0;
  bool logScale = false;
  double position(double value) const;
};
// The scale of `range`: its own ends when given; when automatic, the values seen, widened where
// they are all one value (so that it has a length: ±50 %, or ±1 about zero; a decade either side on
// a log scale) and [0, 1] (or [0.1, 10] on a log scale) when nothing was seen.
ColorScale scaleOf(const Range& range, const ValueRange& seen);

// The springs' range in effect: the one given, else strain's ±0.2 (today's look) for strain and
// auto for tension and energy.
Range effectiveRange(const SpringStyle& springs);

// The auto ranges of a style's three coloured classes, gathered frame by frame.
class StyleRanges {
 public:
  explicit StyleRanges(const Style& style) : style_(style) {}
  // Whether any class is coloured by a quantity over an automatic range: a render must then look
  // at every frame before drawing the first.
  static bool needed(const Style& style);
  void add(const Drawing& frame);
  const ValueRange& particles() const { return particles_; }
  const ValueRange& springs() const { return springs_; }
  const ValueRange& bodies() const { return bodies_; }

 private:
  const Style& style_;
  ValueRange particles_, springs_, bodies_;
  std::vector<double> values_;  // scratch
};

}  // namespace particles::style
