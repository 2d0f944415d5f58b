#pragma once
// Text drawn over a rendered frame (`particles render --hud`): a few lines in the figures' font
// (DejaVu Sans through FreeType), on a translucent panel in the top-left corner, so that a
// video or report frame carries its time, integrator, step and energy.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "plot/figure.hpp"

namespace particles::plot {

struct OverlayStyle {
  double sizePx = 14;               // text height
  bool darkBackground = true;       // light text on a dark panel, or dark on light
  std::filesystem::path fontFile = defaultFontFile();
};

// Draws `lines` onto an 8-bit RGBA image (row-major, top row first, alpha left opaque). Throws
// FigureError if the font cannot be loaded or cairo fails.
void drawTextOverlay(std::uint8_t* rgba, int width, int height, const std::vector<std::string>& lines,
                     const OverlayStyle& style = {});

}  // namespace particles::plot
