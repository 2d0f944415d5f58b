#include "plot/text_overlay.hpp"

#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "plot/cairo_ptr.hpp"
#include "plot/errors.hpp"
#include "plot/font.hpp"
#include "plot/show_text.hpp"

namespace particles::plot {

void drawTextOverlay(std::uint8_t* rgba, int width, int height, const std::vector<std::string>& lines,
                     const OverlayStyle& style) {
  if (lines.empty() || width <= 0 || height <= 0) return;
  const FontFace font(style.fontFile);
  const double pad = std::round(style.sizePx * 0.6);
  const double lineHeight = std::round(style.sizePx * 1.35);

  // Measure on a scratch surface, then draw the panel on one just its size.
  double textWidth = 0;
  {
    SurfacePtr scratch(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1));
    ContextPtr cr(cairo_create(scratch.get()));
    cairo_set_font_face(cr.get(), font.get());
    cairo_set_font_size(cr.get(), style.sizePx);
    for (const std::string& line : lines) {
      cairo_text_extents_t extents;
      cairo_text_extents(cr.get(), line.c_str(), &extents);
      textWidth = std::max(textWidth, extents.x_advance);
    }
    checkCairo(cairo_status(cr.get()), "text overlay", "cairo_text_extents");
  }
  const int panelW = std::min(width, int(std::ceil(textWidth + 2 * pad)));
  const int panelH = std::min(height, int(std::ceil(lines.size() * lineHeight + 2 * pad - (lineHeight - style.sizePx))));
  const int margin = std::min({int(pad), width - panelW, height - panelH});

  SurfacePtr surface(
      cairo_image_surface_create(CAIRO_FORMAT_ARGB32, panelW, panelH));
  checkCairo(cairo_surface_status(surface.get()), "text overlay", "cairo_image_surface_create");
  {
    ContextPtr cr(cairo_create(surface.get()));
    const double bg = style.darkBackground ? 0.0 : 1.0, fg = style.darkBackground ? 0.92 : 0.1;
    cairo_set_source_rgba(cr.get(), bg, bg, bg, 0.6);
    cairo_paint(cr.get());
    cairo_set_source_rgb(cr.get(), fg, fg, fg);
    cairo_set_font_face(cr.get(), font.get());
    cairo_set_font_size(cr.get(), style.sizePx);
    for (size_t i = 0; i < lines.size(); ++i) {
      cairo_move_to(cr.get(), pad, pad + style.sizePx * 0.8 + double(i) * lineHeight);
      showText(cr.get(), lines[i].c_str());
    }
    checkCairo(cairo_status(cr.get()), "text overlay", "cairo_show_text");
  }
  cairo_surface_flush(surface.get());

  // Composite: cairo's ARGB32 is premultiplied, one native-endian uint32 per pixel.
  const unsigned char* src = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < panelH; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(src + size_t(y) * size_t(stride));
    std::uint8_t* dst = rgba + (size_t(y + margin) * size_t(width) + size_t(margin)) * 4;
    for (int x = 0; x < panelW; ++x, dst += 4) {
      const std::uint32_t p = row[x];
      const unsigned a = p >> 24, r = (p >> 16) & 0xff, g = (p >> 8) & 0xff, b = p & 0xff;
      const unsigned keep = 255 - a;
      dst[0] = std::uint8_t(r + (dst[0] * keep + 127) / 255);
      dst[1] = std::uint8_t(g + (dst[1] * keep + 127) / 255);
      dst[2] = std::uint8_t(b + (dst[2] * keep + 127) / 255);
    }
  }
}

}  // namespace particles::plot
