#pragma once
// Text drawn the same on every cairo the project builds with. Internal to plot/.

#include <cairo.h>

namespace particles::plot {

// cairo_show_text at cr's current point, each glyph at a whole device pixel on an image surface:
// cairo 1.16 rounds a glyph's position so, cairo 1.18 draws it at its fraction of a pixel
// (subpixel positioning), which moved the strokes of the same text by up to a pixel (frames'
// labels 115 of 255 apart). Rounded here, text has the same pixels on both. Vector surfaces (SVG,
// PDF) keep the exact positions. The current point ends after the text, as cairo_show_text's does.
void showText(cairo_t* cr, const char* text);

}  // namespace particles::plot
