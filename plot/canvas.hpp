#pragma once
// Drawing primitives shared by the charts, in pixels with y pointing down: text with an optional
// superscript, aligned to a point; crisp hairlines; filled rectangles. Internal to plot/.

#include <cairo.h>

#include "plot/palette.hpp"
#include "plot/ticks.hpp"

namespace particles::plot {

// Text sizes in pixels, chosen to read comfortably at 100 % on a 1200 × 800 figure.
inline constexpr double kTitleSizePx = 16;
inline constexpr double kAxisLabelSizePx = 14;
inline constexpr double kTickLabelSizePx = 13;
inline constexpr double kLegendSizePx = 13;

enum class HAlign { Left, Center, Right };
enum class VAlign {
  Baseline,
  Top,     // the top of capitals and digits is at y
  Middle,  // capitals and digits are centred on y
};

struct Rect {
  double x, y, w, h;
  double right() const { return x + w; }
  double bottom() const { return y + h; }
};

class Canvas {
 public:
  Canvas(cairo_t* cr, cairo_font_face_t* font);

  cairo_t* cr() const { return cr_; }

  // Advance width of a label at `sizePx` (the superscript at 70 % of it).
  double textWidth(const Label& label, double sizePx) const;
  // Height of capitals and digits at `sizePx`.
  static double capHeight(double sizePx);

  // `angle` in radians, counter-clockwise as seen (−π/2 in cairo's frame): π/2 for y-axis labels.
  void text(const Label& label, double x, double y, double sizePx, HAlign h, VAlign v, Rgb colour,
            double angle = 0) const;

  // A 1-pixel line on pixel centres, so it stays one sharp pixel wide in the PNG.
  void hairline(double x0, double y0, double x1, double y1, Rgb colour) const;
  void fillRect(const Rect& r, Rgb colour, double alpha = 1.0) const;
  // The outline of r as a hairline.
  void frame(const Rect& r, Rgb colour) const;

 private:
  cairo_t* cr_;
  cairo_font_face_t* font_;
};

// x rounded to the nearest pixel centre (n + 0.5): hairlines drawn there cover whole pixels.
double pixelCentre(double x);

}  // namespace particles::plot
