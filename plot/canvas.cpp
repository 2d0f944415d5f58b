#include "plot/canvas.hpp"

#include <cmath>

#include "plot/show_text.hpp"

namespace particles::plot {

namespace {

constexpr double kSuperscriptScale = 0.7;
constexpr double kSuperscriptRise = 0.42;  // × size, baseline of the superscript above the main one
// DejaVu Sans: capitals and digits are 1493 of 2048 units per em tall.
constexpr double kCapHeightPerEm = 1493.0 / 2048.0;

void setColour(cairo_t* cr, Rgb c, double alpha = 1.0) {
  cairo_set_source_rgba(cr, c.r, c.g, c.b, alpha);
}

double advance(cairo_t* cr, const std::string& s) {
  if (s.empty()) return 0;
  cairo_text_extents_t extents;
  cairo_text_extents(cr, s.c_str(), &extents);
  return extents.x_advance;
}

}  // namespace

Canvas::Canvas(cairo_t* cr, cairo_font_face_t* font) : cr_(cr), font_(font) {
  cairo_set_font_face(cr_, font_);
  // Unhinted metrics: text is laid out the same in the SVG and the PNG. Grey anti-aliasing, not
  // sub-pixel: a PNG in a report should not have colour fringes.
  cairo_font_options_t* options = cairo_font_options_create();
  cairo_font_options_set_hint_metrics(options, CAIRO_HINT_METRICS_OFF);
  cairo_font_options_set_hint_style(options, CAIRO_HINT_STYLE_SLIGHT);
  cairo_font_options_set_antialias(options, CAIRO_ANTIALIAS_GRAY);
  cairo_set_font_options(cr_, options);
  cairo_font_options_destroy(options);
}

double Canvas::capHeight(double sizePx) {
  return kCapHeightPerEm * sizePx;
}

double Canvas::textWidth(const Label& label, double sizePx) const {
  cairo_set_font_size(cr_, sizePx);
  double w = advance(cr_, label.text);
  if (!label.superscript.empty()) {
    cairo_set_font_size(cr_, sizePx * kSuperscriptScale);
    w += advance(cr_, label.superscript);
  }
  return w;
}

void Canvas::text(const Label& label, double x, double y, double sizePx, HAlign h, VAlign v, Rgb colour,
                  double angle) const {
  const double width = textWidth(label, sizePx);
  double dx = 0, dy = 0;
  if (h == HAlign::Center) dx = -width / 2;
  if (h == HAlign::Right) dx = -width;
  if (v == VAlign::Top) dy = capHeight(sizePx);
  if (v == VAlign::Middle) dy = capHeight(sizePx) / 2;

  cairo_save(cr_);
  cairo_translate(cr_, x, y);
  cairo_rotate(cr_, -angle);
  setColour(cr_, colour);
  cairo_set_font_size(cr_, sizePx);
  cairo_move_to(cr_, dx, dy);
  showText(cr_, label.text.c_str());
  if (!label.superscript.empty()) {
    cairo_set_font_size(cr_, sizePx * kSuperscriptScale);
    cairo_rel_move_to(cr_, 0, -kSuperscriptRise * sizePx);
    showText(cr_, label.superscript.c_str());
  }
  cairo_restore(cr_);
}

void Canvas::hairline(double x0, double y0, double x1, double y1, Rgb colour) const {
  // Horizontal and vertical lines (all that the charts draw) land on pixel centres.
  if (x0 == x1) x0 = x1 = pixelCentre(x0);
  if (y0 == y1) y0 = y1 = pixelCentre(y0);
  cairo_save(cr_);
  setColour(cr_, colour);
  cairo_set_line_width(cr_, 1.0);
  cairo_set_line_cap(cr_, CAIRO_LINE_CAP_SQUARE);
  cairo_move_to(cr_, x0, y0);
  cairo_line_to(cr_, x1, y1);
  cairo_stroke(cr_);
  cairo_restore(cr_);
}

void Canvas::fillRect(const Rect& r, Rgb colour, double alpha) const {
  cairo_save(cr_);
  setColour(cr_, colour, alpha);
  cairo_rectangle(cr_, r.x, r.y, r.w, r.h);
  cairo_fill(cr_);
  cairo_restore(cr_);
}

void Canvas::frame(const Rect& r, Rgb colour) const {
  cairo_save(cr_);
  setColour(cr_, colour);
  cairo_set_line_width(cr_, 1.0);
  const double x0 = pixelCentre(r.x), y0 = pixelCentre(r.y);
  cairo_rectangle(cr_, x0, y0, pixelCentre(r.right()) - x0, pixelCentre(r.bottom()) - y0);
  cairo_stroke(cr_);
  cairo_restore(cr_);
}

double pixelCentre(double x) {
  return std::floor(x) + 0.5;
}

}  // namespace particles::plot
