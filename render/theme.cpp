#include "render/theme.hpp"

#include <algorithm>

namespace particles::render {

Palette theme(ThemeName name) {
  if (name == ThemeName::light) {
    return {
        .background = {255, 255, 255},
        .particle = {25, 25, 30},
        .fixedParticle = {200, 110, 0},
        .springCompressed = {30, 90, 220},
        .springRest = {140, 140, 145},
        .springStretched = {215, 35, 30},
        .rod = {40, 40, 45},
        .guide = {0, 135, 75},
        .bodyFill = {175, 198, 232},
        .bodyOutline = {30, 60, 115},
        .colliderFill = {218, 220, 226},
        .colliderOutline = {110, 115, 128},
        .mouse = {250, 170, 0},
        .mouseOutline = {0, 0, 0},
    };
  }
  return {
      .background = {18, 20, 24},
      .particle = {235, 235, 235},
      .fixedParticle = {255, 190, 50},
      .springCompressed = {70, 145, 255},
      .springRest = {135, 138, 145},
      .springStretched = {255, 75, 55},
      .rod = {225, 225, 230},
      .guide = {90, 200, 130},
      .bodyFill = {55, 85, 135},
      .bodyOutline = {175, 205, 245},
      .colliderFill = {44, 48, 56},
      .colliderOutline = {115, 124, 140},
      .mouse = {255, 215, 0},
      .mouseOutline = {0, 0, 0},
  };
}

namespace {

// std::lround's value (halves away from zero) for |v| < 2^31, inline: g++ calls libm's for
// std::lround, and mix runs for each channel of every spring of every frame. v − trunc(v) is
// v's fraction, which a double holds exactly, so the comparisons with ±0.5 are exact.
long roundHalfAwayFromZero(double v) {
  const long whole = static_cast<long>(v);
  const double fraction = v - static_cast<double>(whole);
  return whole + (fraction >= 0.5 ? 1 : 0) - (fraction <= -0.5 ? 1 : 0);
}

}  // namespace

Rgb mix(Rgb a, Rgb b, double t) {
  auto m = [t](unsigned char x, unsigned char y) {
    return static_cast<unsigned char>(roundHalfAwayFromZero(double(x) + (double(y) - double(x)) * t));
  };
  return {m(a.r, b.r), m(a.g, b.g), m(a.b, b.b)};
}

Rgb springColor(const Palette& c, double strain, double strainForFullColor) {
  const double t = std::clamp(strain / strainForFullColor, -1.0, 1.0);
  return t < 0 ? mix(c.springRest, c.springCompressed, -t) : mix(c.springRest, c.springStretched, t);
}

}  // namespace particles::render
