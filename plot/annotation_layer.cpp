#include "plot/annotation_layer.hpp"

#include <algorithm>
#include <cmath>

#include "plot/errors.hpp"
#include "plot/show_text.hpp"

namespace particles::plot {

namespace {

constexpr const char* kWhat = "frame annotations";

// The smallest text `fit` shrinks to: smaller is not read, only seen.
constexpr double kLeastTextPx = 6.0;

}  // namespace

PanelInk panelInk(bool darkTheme) {
  return darkTheme ? PanelInk{0.0, 0.6, 0.92} : PanelInk{1.0, 0.6, 0.1};
}

FontFace loadAnnotationFont(const std::filesystem::path& file) {
  try {
    return FontFace(file);
  } catch (const FigureError& e) {
    throw FigureError(std::string(kWhat) + ": " + e.what());
  }
}

Typesetter::Typesetter(cairo_font_face_t* face)
    : face_(face), scratch_(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1)), cr_(cairo_create(scratch_.get())) {
  checkCairo(cairo_status(cr_.get()), kWhat, "cairo_create");
  cairo_set_font_face(cr_.get(), face_);
}

double Typesetter::advance(const std::string& text, double sizePx) const {
  cairo_set_font_size(cr_.get(), sizePx);
  cairo_text_extents_t extents;
  cairo_text_extents(cr_.get(), text.c_str(), &extents);
  checkCairo(cairo_status(cr_.get()), kWhat, "cairo_text_extents");
  return extents.x_advance;
}

double Typesetter::advance(const Label& label, double sizePx) const {
  return advance(label.text, sizePx) + (label.superscript.empty() ? 0.0 : advance(label.superscript, 0.7 * sizePx));
}

double Typesetter::ascent(double sizePx) const {
  cairo_set_font_size(cr_.get(), sizePx);
  cairo_font_extents_t extents;
  cairo_font_extents(cr_.get(), &extents);
  return extents.ascent;
}

double Typesetter::descent(double sizePx) const {
  cairo_set_font_size(cr_.get(), sizePx);
  cairo_font_extents_t extents;
  cairo_font_extents(cr_.get(), &extents);
  return extents.descent;
}

double Typesetter::fit(const std::string& text, double sizePx, double widthPx) const {
  const double width = advance(text, sizePx);
  if (width <= widthPx || width <= 0) return sizePx;
  return std::max(std::min(kLeastTextPx, sizePx), sizePx * std::max(widthPx, 0.0) / width);
}

void Typesetter::show(cairo_t* cr, const Label& label, double x, double baseline, double sizePx) const {
  cairo_set_font_face(cr, face_);
  cairo_set_font_size(cr, sizePx);
  cairo_move_to(cr, x, baseline);
  showText(cr, label.text.c_str());
  if (!label.superscript.empty()) {
    cairo_set_font_size(cr, 0.7 * sizePx);
    cairo_rel_move_to(cr, 0, -0.45 * sizePx);
    showText(cr, label.superscript.c_str());
  }
  checkCairo(cairo_status(cr), kWhat, "cairo_show_text");
}

PixelBox visiblePart(const PixelBox& box, int width, int height) {
  const int x0 = std::max(box.x, 0), y0 = std::max(box.y, 0);
  const int x1 = std::min(box.x + std::max(box.width, 0), width),
            y1 = std::min(box.y + std::max(box.height, 0), height);
  if (x1 <= x0 || y1 <= y0) return {};
  return {x0, y0, x1 - x0, y1 - y0};
}

Layer::Layer(const PixelBox& box, int width, int height, const PanelInk& ink, cairo_font_face_t* face)
    : visible_(visiblePart(box, width, height)),
      surface_(
          cairo_image_surface_create(CAIRO_FORMAT_ARGB32, std::max(visible_.width, 1), std::max(visible_.height, 1))),
      cr_(cairo_create(surface_.get())) {
  checkCairo(cairo_surface_status(surface_.get()), kWhat, "cairo_image_surface_create");
  checkCairo(cairo_status(cr_.get()), kWhat, "cairo_create");
  cairo_t* cr = cr_.get();
  if (visible_.empty()) return;  // composite() draws nothing
  cairo_set_source_rgba(cr, ink.panel, ink.panel, ink.panel, ink.panelAlpha);
  cairo_paint(cr);
  cairo_translate(cr, -visible_.x, -visible_.y);
  cairo_set_source_rgb(cr, ink.ink, ink.ink, ink.ink);
  cairo_set_font_face(cr, face);
}

void Layer::setOpaque(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  const int sx = x - visible_.x, sy = y - visible_.y;
  if (sx < 0 || sy < 0 || sx >= visible_.width || sy >= visible_.height) return;
  if (!pixelsWritten_) cairo_surface_flush(surface_.get());  // cairo's drawing first
  pixelsWritten_ = true;
  unsigned char* data = cairo_image_surface_get_data(surface_.get());
  const int stride = cairo_image_surface_get_stride(surface_.get());
  auto* pixel = reinterpret_cast<std::uint32_t*>(data + std::size_t(sy) * std::size_t(stride)) + sx;
  *pixel = 0xFF000000u | (std::uint32_t(r) << 16) | (std::uint32_t(g) << 8) | std::uint32_t(b);
}

void Layer::composite(std::uint8_t* rgba, int width) const {
  checkCairo(cairo_status(cr_.get()), kWhat, "drawing a panel");
  if (visible_.empty()) return;
  if (pixelsWritten_) cairo_surface_mark_dirty(surface_.get());
  cairo_surface_flush(surface_.get());
  // cairo's ARGB32: premultiplied, one native-endian uint32 a pixel. The frame's alpha is straight:
  // "over" is a_out = a_s + a_d (1 − a_s), c_out = (c_s a_s + c_d a_d (1 − a_s)) / a_out, and
  // cairo's pixel holds c_s a_s already (Porter and Duff, "Compositing Digital Images", 1984).
  const unsigned char* data = cairo_image_surface_get_data(surface_.get());
  const int stride = cairo_image_surface_get_stride(surface_.get());
  for (int y = 0; y < visible_.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + std::size_t(y) * std::size_t(stride));
    std::uint8_t* dst = rgba + (std::size_t(visible_.y + y) * std::size_t(width) + std::size_t(visible_.x)) * 4;
    for (int x = 0; x < visible_.width; ++x, dst += 4) {
      const std::uint32_t p = row[x];
      const unsigned sa = p >> 24;
      if (sa == 0) continue;
      const double src[3] = {double((p >> 16) & 0xFFu), double((p >> 8) & 0xFFu), double(p & 0xFFu)};
      if (sa == 255) {
        for (int c = 0; c < 3; ++c) dst[c] = std::uint8_t(src[c]);
        dst[3] = 255;
        continue;
      }
      const double keep = (1.0 - sa / 255.0) * (dst[3] / 255.0);  // the frame's share, a_d (1 − a_s)
      const double alpha = sa / 255.0 + keep;
      for (int c = 0; c < 3; ++c) {
        const double value = (src[c] / 255.0 + dst[c] / 255.0 * keep) / alpha;
        dst[c] = std::uint8_t(std::lround(std::min(1.0, value) * 255.0));
      }
      dst[3] = std::uint8_t(std::lround(std::min(1.0, alpha) * 255.0));
    }
  }
}

}  // namespace particles::plot
