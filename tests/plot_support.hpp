#pragma once
// Helpers for the figure tests: a fresh temporary directory, an SVG read back with expat into a
// flat list of elements, and a PNG decoded with cairo into pixels.

#include <cairo.h>
#include <expat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "plot/palette.hpp"

namespace particles::test {

// A new, empty directory under the system's temporary directory, removed with its contents.
class TempDir {
 public:
  TempDir() {
    static std::atomic<unsigned> counter{0};
    path_ = std::filesystem::temp_directory_path() /
            ("particles_plot_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : std::filesystem::directory_iterator(path_)) names.push_back(e.path().filename().string());
    return names;
  }

 private:
  std::filesystem::path path_;
};

inline std::vector<std::uint8_t> readBytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text;  // character data directly inside it
};

// The document's elements in order. Throws with expat's message and line if it is not well-formed.
inline std::vector<XmlElement> parseXml(const std::vector<std::uint8_t>& bytes) {
  struct State {
    std::vector<XmlElement> elements;
    std::vector<std::size_t> open;
  } state;
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &state);
  XML_SetElementHandler(
      parser,
      [](void* data, const XML_Char* name, const XML_Char** attrs) {
        auto* s = static_cast<State*>(data);
        XmlElement e{name, {}, {}};
        for (int i = 0; attrs[i]; i += 2) e.attributes[attrs[i]] = attrs[i + 1];
        s->open.push_back(s->elements.size());
        s->elements.push_back(std::move(e));
      },
      [](void* data, const XML_Char*) { static_cast<State*>(data)->open.pop_back(); });
  XML_SetCharacterDataHandler(parser, [](void* data, const XML_Char* text, int length) {
    auto* s = static_cast<State*>(data);
    if (!s->open.empty()) s->elements[s->open.back()].text.append(text, static_cast<std::size_t>(length));
  });
  // expat 2.9 deprecates the line number of the platform's size for a 64-bit one it adds.
#if XML_MAJOR_VERSION > 2 || (XML_MAJOR_VERSION == 2 && XML_MINOR_VERSION >= 9)
  const auto line = [&] { return XML_GetCurrentLineNumber64(parser); };
#else
  const auto line = [&] { return XML_GetCurrentLineNumber(parser); };
#endif
  const bool ok = XML_Parse(parser, reinterpret_cast<const char*>(bytes.data()), static_cast<int>(bytes.size()), 1) ==
                  XML_STATUS_OK;
  const std::string error =
      ok ? "" : std::string(XML_ErrorString(XML_GetErrorCode(parser))) + " at line " + std::to_string(line());
  XML_ParserFree(parser);
  if (!ok) throw std::runtime_error("SVG is not well-formed XML: " + error);
  return state.elements;
}

// The value of `property` ("fill", "stroke", "stroke-width") an element sets itself, or "". cairo
// 1.16 writes a CSS style attribute (style="fill:none;stroke:rgb(…);…", spaces allowed around its
// parts), 1.18 presentation attributes (fill="none" stroke="rgb(…)"): the same meaning to SVG.
inline std::string styleProperty(const XmlElement& e, const std::string& property) {
  const auto trimmed = [](const std::string& t) {
    const std::size_t a = t.find_first_not_of(' '), b = t.find_last_not_of(' ');
    return a == std::string::npos ? std::string() : t.substr(a, b - a + 1);
  };
  if (const auto it = e.attributes.find("style"); it != e.attributes.end()) {
    const std::string& style = it->second;
    std::size_t pos = 0;
    while (pos < style.size()) {
      std::size_t end = style.find(';', pos);
      if (end == std::string::npos) end = style.size();
      const std::string declaration = style.substr(pos, end - pos);
      const std::size_t colon = declaration.find(':');
      if (colon != std::string::npos && trimmed(declaration.substr(0, colon)) == property) {
        return trimmed(declaration.substr(colon + 1));
      }
      pos = end + 1;
    }
  }
  const auto attribute = e.attributes.find(property);
  return attribute == e.attributes.end() ? "" : trimmed(attribute->second);
}

// Whether a CSS colour as cairo writes it, "rgb(12.156863%,46.666667%,70.588235%)" (1.16),
// "rgb(12.156863%, 46.666667%, 70.588235%)" (1.18), "rgb(31,119,180)" or "#1f77b4", is `c` (to
// within a step of 8 bits).
inline bool sameColour(const std::string& css, plot::Rgb c) {
  double v[3];
  if (css.size() == 7 && css[0] == '#') {
    for (int i = 0; i < 3; ++i) v[i] = std::stoi(css.substr(1 + 2 * i, 2), nullptr, 16) / 255.0;
  } else if (css.rfind("rgb(", 0) == 0) {
    std::size_t pos = 4;
    for (int i = 0; i < 3; ++i) {
      std::size_t used = 0;
      v[i] = std::stod(css.substr(pos), &used);
      pos += used;
      if (css[pos] == '%') {
        v[i] /= 100;
        ++pos;
      } else {
        v[i] /= 255;
      }
      ++pos;  // ',' or ')'
    }
  } else {
    return false;
  }
  return std::fabs(v[0] - c.r) < 0.6 / 255 && std::fabs(v[1] - c.g) < 0.6 / 255 && std::fabs(v[2] - c.b) < 0.6 / 255;
}

// Vertices (M and L commands) and sub-paths (M commands) of an SVG path's "d".
struct PathShape {
  int vertices = 0, subpaths = 0, curves = 0;
};
inline PathShape pathShape(const XmlElement& path) {
  PathShape shape;
  const auto it = path.attributes.find("d");
  if (it == path.attributes.end()) return shape;
  std::string d = it->second;
  // cairo closes a filled path with "Z M x y" back at its start: that M is no new sub-path.
  for (std::size_t i = 0; i < d.size(); ++i) {
    const char c = d[i];
    if (c == 'M' && !(i >= 2 && d[i - 2] == 'Z')) {
      ++shape.subpaths;
      ++shape.vertices;
    }
    if (c == 'L') ++shape.vertices;
    if (c == 'C') ++shape.curves;
  }
  return shape;
}

// Every coordinate pair of an SVG path's "d", in order (Bézier control points included).
struct PathPoint {
  double x, y;
};
inline std::vector<PathPoint> pathPoints(const XmlElement& path) {
  const auto it = path.attributes.find("d");
  if (it == path.attributes.end()) return {};
  const std::string& d = it->second;
  // Each number is read in place (strtod from its first character): a copy of the rest of the path
  // per number would make a dense series' path of ~100,000 numbers quadratic in its length.
  std::vector<double> numbers;
  for (std::size_t i = 0; i < d.size();) {
    const char c = d[i];
    if (c == '-' || c == '.' || (c >= '0' && c <= '9')) {
      char* end = nullptr;
      const double value = std::strtod(d.c_str() + i, &end);
      if (end == d.c_str() + i) throw std::invalid_argument("an SVG path's d holds no number at " + d.substr(i, 20));
      numbers.push_back(value);
      i = std::size_t(end - d.c_str());
    } else {
      ++i;
    }
  }
  std::vector<PathPoint> points;
  for (std::size_t k = 0; k + 1 < numbers.size(); k += 2) points.push_back({numbers[k], numbers[k + 1]});
  return points;
}

// The bounding box of an SVG path's points (Bézier control points included: for a circle the box
// is symmetric about its centre).
struct PathBounds {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  double centreX() const { return (x0 + x1) / 2; }
  double centreY() const { return (y0 + y1) / 2; }
};
inline PathBounds pathBounds(const XmlElement& path) {
  PathBounds b;
  for (const PathPoint& p : pathPoints(path)) {
    b.x0 = std::min(b.x0, p.x);
    b.x1 = std::max(b.x1, p.x);
    b.y0 = std::min(b.y0, p.y);
    b.y1 = std::max(b.y1, p.y);
  }
  return b;
}

// The plot frames of a figure: rectangles stroked in ink (4 vertices, one sub-path), widest first.
inline std::vector<PathBounds> plotFrames(const std::vector<XmlElement>& svg) {
  std::vector<PathBounds> frames;
  for (const XmlElement& e : svg) {
    if (e.name != "path" || !sameColour(styleProperty(e, "stroke"), plot::kInk)) continue;
    const PathShape shape = pathShape(e);
    if (shape.vertices == 4 && shape.subpaths == 1 && shape.curves == 0) frames.push_back(pathBounds(e));
  }
  std::stable_sort(frames.begin(), frames.end(),
                   [](const PathBounds& a, const PathBounds& b) { return a.x1 - a.x0 > b.x1 - b.x0; });
  return frames;
}

// Glyphs whose origin lies in `box`: cairo draws text as one <use> element per glyph (spaces too),
// at the glyph's origin on the baseline.
inline long glyphsIn(const std::vector<XmlElement>& svg, const PathBounds& box) {
  return std::count_if(svg.begin(), svg.end(), [&](const XmlElement& e) {
    if (e.name != "use" || !e.attributes.count("x") || !e.attributes.count("y")) return false;
    const double x = std::stod(e.attributes.at("x")), y = std::stod(e.attributes.at("y"));
    return x >= box.x0 && x <= box.x1 && y >= box.y0 && y <= box.y1;
  });
}

// An RGB24 image decoded from PNG bytes.
struct Pixels {
  int width = 0, height = 0;
  std::vector<std::uint32_t> argb;  // row-major, 0x00RRGGBB
  std::uint32_t at(int x, int y) const { return argb[static_cast<std::size_t>(y) * width + x]; }
  // Luminance 0…255.
  double luminance(int x, int y) const {
    const std::uint32_t p = at(x, y);
    return 0.2126 * ((p >> 16) & 0xff) + 0.7152 * ((p >> 8) & 0xff) + 0.0722 * (p & 0xff);
  }
  // Pixels in [x0, x1) × [y0, y1) darker than half grey: text and black lines.
  int darkPixels(int x0, int y0, int x1, int y1) const {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += luminance(x, y) < 128;
    return n;
  }
  // Whether the pixel is colour `c`, to within 8 levels of 255 in each channel.
  bool is(int x, int y, plot::Rgb c) const {
    const std::uint32_t p = at(x, y);
    return std::fabs(((p >> 16) & 0xff) - 255 * c.r) <= 8 && std::fabs(((p >> 8) & 0xff) - 255 * c.g) <= 8 &&
           std::fabs((p & 0xff) - 255 * c.b) <= 8;
  }
  // Pixels in the rectangle that are not pure white.
  int inkedPixels(int x0, int y0, int x1, int y1) const {
    int n = 0;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) n += (at(x, y) & 0xffffff) != 0xffffff;
    return n;
  }
};

inline Pixels decodePng(const std::vector<std::uint8_t>& bytes) {
  struct Reader {
    const std::vector<std::uint8_t>* bytes;
    std::size_t pos = 0;
  } reader{&bytes};
  cairo_surface_t* s = cairo_image_surface_create_from_png_stream(
      [](void* closure, unsigned char* data, unsigned int length) {
        auto* r = static_cast<Reader*>(closure);
        if (r->pos + length > r->bytes->size()) return CAIRO_STATUS_READ_ERROR;
        std::copy_n(r->bytes->data() + r->pos, length, data);
        r->pos += length;
        return CAIRO_STATUS_SUCCESS;
      },
      &reader);
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    const std::string message = cairo_status_to_string(cairo_surface_status(s));
    cairo_surface_destroy(s);
    throw std::runtime_error("PNG does not decode: " + message);
  }
  Pixels p;
  p.width = cairo_image_surface_get_width(s);
  p.height = cairo_image_surface_get_height(s);
  const int stride = cairo_image_surface_get_stride(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  for (int y = 0; y < p.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    p.argb.insert(p.argb.end(), row, row + p.width);
  }
  cairo_surface_destroy(s);
  return p;
}

}  // namespace particles::test
