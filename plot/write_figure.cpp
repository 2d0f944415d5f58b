// From a Figure to bytes (a cairo SVG, PDF or image surface) and from bytes to a file (a temporary name
// beside the destination, renamed when complete).

#include <cairo-pdf.h>
#include <cairo-svg.h>
#include <cairo.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <memory>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "plot/cairo_ptr.hpp"
#include "plot/canvas.hpp"
#include "plot/charts.hpp"
#include "plot/errors.hpp"
#include "output/output_error.hpp"
#include "output/pending_output.hpp"
#include "plot/figure.hpp"
#include "plot/font.hpp"

namespace particles::plot {

namespace {

// cairo's write callback: appends to a byte vector. Must not throw into C.
cairo_status_t appendBytes(void* closure, const unsigned char* data, unsigned int length) {
  try {
    auto* out = static_cast<std::vector<std::uint8_t>*>(closure);
    out->insert(out->end(), data, data + length);
    return CAIRO_STATUS_SUCCESS;
  } catch (...) {
    return CAIRO_STATUS_WRITE_ERROR;
  }
}

void validate(const Figure& figure) {
  if (figure.widthPx < 200 || figure.heightPx < 150 || figure.widthPx > 20000 || figure.heightPx > 20000) {
    throw FigureError("figure size " + std::to_string(figure.widthPx) + "x" + std::to_string(figure.heightPx) +
                      " px is outside 200x150 to 20000x20000");
  }
  if (const auto* line = std::get_if<LineChart>(&figure.chart)) {
    for (const Panel& p : line->panels) {
      for (const Series& s : p.series) {
        if (s.x.size() != s.y.size()) {
          throw FigureError("series '" + s.name + "' has " + std::to_string(s.x.size()) + " x values but " +
                            std::to_string(s.y.size()) + " y values");
        }
      }
    }
  }
  if (const auto* dots = std::get_if<DotChart>(&figure.chart)) {
    for (const DotGroup& g : dots->groups) {
      if (g.values.size() != dots->categories.size()) {
        throw FigureError("dot group '" + g.name + "' has " + std::to_string(g.values.size()) + " values for " +
                          std::to_string(dots->categories.size()) + " categories");
      }
      if (!g.lowerBounds.empty() && g.lowerBounds.size() != g.values.size()) {
        throw FigureError("dot group '" + g.name + "' has " + std::to_string(g.lowerBounds.size()) +
                          " lower-bound flags for " + std::to_string(g.values.size()) + " values");
      }
    }
    if (!dots->references.empty() && dots->references.size() != dots->categories.size()) {
      throw FigureError("dot chart has " + std::to_string(dots->references.size()) + " references for " +
                        std::to_string(dots->categories.size()) + " categories");
    }
  }
}

void draw(cairo_t* cr, const FontFace& font, const Figure& figure) {
  cairo_set_source_rgb(cr, kBackground.r, kBackground.g, kBackground.b);
  cairo_paint(cr);
  const Canvas canvas(cr, font.get());
  std::visit(
      [&](const auto& chart) {
        if constexpr (std::is_same_v<std::decay_t<decltype(chart)>, LineChart>) {
          drawLineChart(canvas, figure, chart);
        } else {
          drawDotChart(canvas, figure, chart);
        }
      },
      figure.chart);
  checkCairo(cairo_status(cr), "cannot draw figure", "drawing");
}

std::string escapeXml(const std::string& s) {
  std::string out;
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      default: out += c;
    }
  }
  return out;
}

// cairo names the SVG's top group after the surface's process-wide serial number
// (<g id="surface42">), so the same figure drawn twice in one process would differ in that id.
// Every other id cairo writes (glyphs, clip paths) counts from zero within the document. The
// surface ids are renumbered in order of appearance, and the figure's title becomes the SVG's
// <title>, for screen readers and file browsers.
std::vector<std::uint8_t> normaliseSvg(const std::vector<std::uint8_t>& bytes, const std::string& title) {
  const std::string svg(bytes.begin(), bytes.end());
  std::vector<std::string> seen;  // serial numbers in order of first appearance
  std::string out;
  std::size_t copied = 0;
  for (std::size_t at = svg.find("surface"); at != std::string::npos; at = svg.find("surface", at + 1)) {
    std::size_t end = at + 7;
    while (end < svg.size() && std::isdigit(static_cast<unsigned char>(svg[end]))) ++end;
    if (end == at + 7) continue;  // "surface" not followed by a number
    const std::string serial = svg.substr(at + 7, end - at - 7);
    auto found = std::find(seen.begin(), seen.end(), serial);
    if (found == seen.end()) found = seen.insert(seen.end(), serial);
    out.append(svg, copied, at + 7 - copied);
    out += std::to_string(found - seen.begin() + 1);
    copied = end;
  }
  out.append(svg, copied);
  if (!title.empty()) {
    const std::size_t svgTag = out.find("<svg");
    const std::size_t tagEnd = svgTag == std::string::npos ? svgTag : out.find('>', svgTag);
    if (tagEnd != std::string::npos) out.insert(tagEnd + 1, "\n<title>" + escapeXml(title) + "</title>");
  }
  return {out.begin(), out.end()};
}

std::string lowerExtension(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

// Writes all of `bytes` to `out` through a PendingOutput: the figure appears whole or not at all,
// and an output that cannot be written is a FigureError with the output room's message.
void writeFileAtomically(const std::filesystem::path& out, const std::vector<std::uint8_t>& bytes) {
  try {
    output::PendingOutput pending(out);
    std::size_t done = 0;
    while (done < bytes.size()) {
      const ssize_t n = ::write(pending.fd(), bytes.data() + done, bytes.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) throw output::OutputError("cannot write figure " + out.string() + ": " + std::strerror(errno));
      done += static_cast<std::size_t>(n);
    }
    pending.commit();
  } catch (const output::OutputError& e) {
    throw FigureError(e.what());
  }
}

}  // namespace

ImageFormat formatForPath(const std::filesystem::path& out) {
  const std::string ext = lowerExtension(out);
  if (ext == ".svg") return ImageFormat::Svg;
  if (ext == ".png") return ImageFormat::Png;
  if (ext == ".pdf") return ImageFormat::Pdf;
  throw FigureError("cannot write figure " + out.string() + ": unknown format '" + out.extension().string() +
                    "' (use .svg, .png or .pdf)");
}

std::vector<std::uint8_t> renderFigure(const Figure& figure, ImageFormat format) {
  validate(figure);
  const FontFace font(figure.fontFile);
  std::vector<std::uint8_t> bytes;
  if (format == ImageFormat::Svg) {
    SurfacePtr surface(cairo_svg_surface_create_for_stream(appendBytes, &bytes, figure.widthPx, figure.heightPx));
    checkCairo(cairo_surface_status(surface.get()), "cannot draw figure", "cairo_svg_surface_create_for_stream");
    // Sizes in px, as the PNG: without this cairo declares points and the SVG shows 4/3 larger.
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
    {
      ContextPtr cr(cairo_create(surface.get()));
      draw(cr.get(), font, figure);
    }
    cairo_surface_finish(surface.get());  // writes the document
    checkCairo(cairo_surface_status(surface.get()), "cannot draw figure", "cairo_surface_finish (SVG)");
    return normaliseSvg(bytes, figure.title);
  }
  if (format == ImageFormat::Pdf) {
    // The page is the figure at 96 px per inch (72 pt per inch), as browsers size the SVG: a
    // 1200 × 800 px figure is a 900 × 600 pt page, which LaTeX scales to the column.
    constexpr double kPointsPerPx = 72.0 / 96.0;
    SurfacePtr surface(cairo_pdf_surface_create_for_stream(appendBytes, &bytes, figure.widthPx * kPointsPerPx,
                                                           figure.heightPx * kPointsPerPx));
    checkCairo(cairo_surface_status(surface.get()), "cannot draw figure", "cairo_pdf_surface_create_for_stream");
    // cairo stamps the current time as the creation date: a fixed one keeps the same figure the
    // same bytes (as for SVG and PNG), and the title and creator go in the document information.
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, "2000-01-01T00:00:00Z");
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "particles");
    if (!figure.title.empty()) {
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_TITLE, figure.title.c_str());
    }
    {
      ContextPtr cr(cairo_create(surface.get()));
      cairo_scale(cr.get(), kPointsPerPx, kPointsPerPx);
      draw(cr.get(), font, figure);
    }
    cairo_surface_finish(surface.get());
    checkCairo(cairo_surface_status(surface.get()), "cannot draw figure", "cairo_surface_finish (PDF)");
    return bytes;
  }
  // RGB24: the figure is opaque, and a PNG without alpha is smaller and shows the same everywhere.
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, figure.widthPx, figure.heightPx));
  checkCairo(cairo_surface_status(surface.get()), "cannot draw figure", "cairo_image_surface_create");
  {
    ContextPtr cr(cairo_create(surface.get()));
    draw(cr.get(), font, figure);
  }
  cairo_surface_flush(surface.get());
  checkCairo(cairo_surface_write_to_png_stream(surface.get(), appendBytes, &bytes), "cannot draw figure",
             "cairo_surface_write_to_png_stream");
  return bytes;
}

void writeFigure(const Figure& figure, const std::filesystem::path& out) {
  const ImageFormat format = formatForPath(out);
  std::vector<std::uint8_t> bytes;
  try {
    bytes = renderFigure(figure, format);
  } catch (const FigureError& e) {
    throw FigureError("cannot write figure " + out.string() + ": " + e.what());
  }
  writeFileAtomically(out, bytes);
}

}  // namespace particles::plot
