#pragma once
// The colours of a frame: a palette per theme, and the colour a spring takes from its strain.

#include <particles/choices.hpp>

namespace particles::render {

using ThemeName = particles::Theme;  // include/particles/choices.hpp: dark for the screen, light for printed reports

struct Rgb {
  unsigned char r, g, b;
  bool operator==(const Rgb&) const = default;
};

// A colour with straight alpha (255 opaque), as a style gives shapes theirs (render/frame_look.hpp):
// the shape's covered share of a pixel is multiplied by a / 255. An Rgb is opaque.
struct Rgba {
  unsigned char r = 0, g = 0, b = 0, a = 255;
  Rgba() = default;
  Rgba(unsigned char red, unsigned char green, unsigned char blue, unsigned char alpha = 255)
      : r(red), g(green), b(blue), a(alpha) {}
  Rgba(Rgb c) : r(c.r), g(c.g), b(c.b), a(255) {}  // NOLINT: an opaque colour is a colour
  Rgb rgb() const { return {r, g, b}; }
  bool operator==(const Rgba&) const = default;
};

struct Palette {
  Rgb background;
  Rgb particle, fixedParticle;
  Rgb springCompressed, springRest, springStretched;
  Rgb rod;
  Rgb guide;  // circular wires and rails
  Rgb bodyFill, bodyOutline;
  Rgb colliderFill, colliderOutline;
  Rgb mouse, mouseOutline;
};
Palette theme(ThemeName name);

// a + (b − a)·t per channel, rounded to the nearest level; t in [0, 1].
Rgb mix(Rgb a, Rgb b, double t);

// A spring's colour: the at-rest colour at strain 0, moving linearly towards the compressed
// (strain < 0) or stretched (strain > 0) colour, which it reaches at |strain| ≥ strainForFullColor
// (> 0). Strain as in core/drawing.hpp: |l| / rest − 1.
Rgb springColor(const Palette& theme, double strain, double strainForFullColor);

}  // namespace particles::render
