#pragma once
// A frame's style (style/style.hpp) resolved, for one frame, into what each shape looks like: every
// particle's colour and radius, every spring's colour, every body's fill and outline, and the
// strokes a style adds (trails, arrows). Made between the Drawing and the rasters (resolveLook,
// here), so that no raster knows what a style is: the frame's mesh (render/frame_mesh.hpp) reads
// colours from it, and every path (cpu, tiles, triangles, resident) draws the same.
//
// An empty list means "as without a style": the theme's colours (render/theme.hpp), the render's
// radius and widths, strain colours for springs.

#include <vector>

#include "core/drawing.hpp"
#include "render/theme.hpp"

namespace particles::render {

struct FrameLook {
  // One per particle of the Drawing, or empty.
  std::vector<Rgba> particleColors;
  std::vector<float> particleRadiiPx;
  // One per spring, those by position (Drawing::springs) then those by index (springTopology), or empty.
  std::vector<Rgba> springColors;
  // One per body, or empty.
  std::vector<Rgba> bodyFills;
  std::vector<Rgba> bodyOutlines;

  // A straight piece of a trail, in world coordinates, drawn above the bodies and below the
  // particles; a trail fades by its pieces' alpha.
  struct Stroke {
    Vec2 a, b;
    float widthPx;
    Rgba color;
  };
  std::vector<Stroke> trails;
  // An arrow from `from` to `to` (world), drawn above the particles: a shaft of widthPx and a head.
  struct Arrow {
    Vec2 from, to;
    float widthPx;
    Rgba color;
  };
  std::vector<Arrow> arrows;

  // Whether the look changes nothing (every list empty).
  bool empty() const {
    return particleColors.empty() && particleRadiiPx.empty() && springColors.empty() && bodyFills.empty() &&
           bodyOutlines.empty() && trails.empty() && arrows.empty();
  }
};

}  // namespace particles::render
