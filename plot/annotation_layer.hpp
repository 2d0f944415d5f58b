#pragma once
// What frame_annotations.cpp draws with (internal to plot/): the font and its text, measured and
// shown, and a panel drawn on a cairo surface of its own and composited over the frame.

#include <cairo.h>

#include <cstdint>
#include <filesystem>
#include <string>

#include "plot/cairo_ptr.hpp"
#include "plot/font.hpp"
#include "plot/frame_annotations.hpp"
#include "plot/ticks.hpp"

namespace particles::plot {

// A panel's grey and opacity and the grey of what is drawn on it: the --hud panel's
// (plot/text_overlay.cpp), light on dark or dark on light.
struct PanelInk {
  double panel, panelAlpha, ink;
};
PanelInk panelInk(bool darkTheme);

// The font from its file; FigureError "frame annotations: …" naming the file when it cannot be read.
FontFace loadAnnotationFont(const std::filesystem::path& file);

// Text in the font at a size in pixels: measured on a scratch surface, shown on a layer.
class Typesetter {
 public:
  explicit Typesetter(cairo_font_face_t* face);
  double advance(const std::string& text, double sizePx) const;
  double advance(const Label& label, double sizePx) const;  // with its superscript
  double ascent(double sizePx) const;
  double descent(double sizePx) const;
  double lineHeight(double sizePx) const { return ascent(sizePx) + descent(sizePx); }
  // From a line's middle down to the baseline that centres the text on it.
  double middleToBaseline(double sizePx) const { return (ascent(sizePx) - descent(sizePx)) / 2; }
  // sizePx, or the smaller size at which `text` fits in widthPx, down to 6 px (then it is clipped).
  double fit(const std::string& text, double sizePx, double widthPx) const;
  // The label with its left end at x on `baseline`, a superscript at 70 % raised by 45 % of the size.
  void show(cairo_t* cr, const Label& label, double x, double baseline, double sizePx) const;

 private:
  cairo_font_face_t* face_;
  SurfacePtr scratch_;
  ContextPtr cr_;
};

// The part of `box` inside a width × height frame (empty when none is).
PixelBox visiblePart(const PixelBox& box, int width, int height);

// A panel: a surface over the visible part of `box`, painted with the panel's grey, whose context
// draws in frame coordinates in the ink's grey with the font; composited over the frame at the end.
class Layer {
 public:
  Layer(const PixelBox& box, int width, int height, const PanelInk& ink, cairo_font_face_t* face);
  cairo_t* cr() const { return cr_.get(); }
  // One pixel (frame coordinates) made opaque r, g, b, after cairo's drawing; nothing outside.
  void setOpaque(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b);
  // The layer over the frame (straight alpha): pixels the layer leaves transparent are kept as
  // they are, alpha included. Throws FigureError if a cairo call on the layer failed.
  void composite(std::uint8_t* rgba, int width) const;

 private:
  PixelBox visible_;
  SurfacePtr surface_;
  ContextPtr cr_;
  bool pixelsWritten_ = false;
};

}  // namespace particles::plot
