#include "plot/show_text.hpp"

#include <cmath>

namespace particles::plot {

void showText(cairo_t* cr, const char* text) {
  if (cairo_surface_get_type(cairo_get_target(cr)) != CAIRO_SURFACE_TYPE_IMAGE || !cairo_has_current_point(cr)) {
    cairo_show_text(cr, text);
    return;
  }
  double x = 0, y = 0;
  cairo_get_current_point(cr, &x, &y);
  cairo_glyph_t* glyphs = nullptr;
  int count = 0;
  const cairo_status_t status = cairo_scaled_font_text_to_glyphs(cairo_get_scaled_font(cr), x, y, text, -1, &glyphs,
                                                                 &count, nullptr, nullptr, nullptr);
  if (status != CAIRO_STATUS_SUCCESS) {
    cairo_show_text(cr, text);  // puts cr in the error state the caller checks
    return;
  }
  // Half a pixel rounds up, as cairo 1.16's _cairo_lround does.
  for (int i = 0; i < count; ++i) {
    double dx = glyphs[i].x, dy = glyphs[i].y;
    cairo_user_to_device(cr, &dx, &dy);
    dx = std::floor(dx + 0.5);
    dy = std::floor(dy + 0.5);
    cairo_device_to_user(cr, &dx, &dy);
    glyphs[i].x = dx;
    glyphs[i].y = dy;
  }
  cairo_show_glyphs(cr, glyphs, count);
  cairo_glyph_free(glyphs);
  cairo_text_extents_t extents;
  cairo_text_extents(cr, text, &extents);
  cairo_move_to(cr, x + extents.x_advance, y + extents.y_advance);
}

}  // namespace particles::plot
