#pragma once
// The one typeface of every figure, loaded from a font file through FreeType rather than looked
// up through fontconfig: what a figure looks like then depends on the file alone, not on the
// machine's font configuration. Internal to plot/.

#include <cairo.h>

#include <filesystem>

namespace particles::plot {

// Owns a cairo font face made from a TrueType file. cairo may keep the face in its caches after
// this object is gone; the FreeType face and library are released when cairo drops the last
// reference (see font.cpp).
class FontFace {
 public:
  // Throws FigureError naming the file if it is missing or FreeType cannot read it.
  explicit FontFace(const std::filesystem::path& file);
  ~FontFace();
  FontFace(const FontFace&) = delete;
  FontFace& operator=(const FontFace&) = delete;

  cairo_font_face_t* get() const { return face_; }

 private:
  cairo_font_face_t* face_ = nullptr;
};

}  // namespace particles::plot
