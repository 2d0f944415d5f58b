#pragma once
// What a style draws over a rendered frame besides its shapes (docs/scenarios.md, "style"): a
// colour bar, a title, a scale bar and labels beside points. Plain data, filled by the renderer's
// side (render/styled_run.hpp) from a style, and one function that draws it, as the --hud panel is
// drawn (plot/text_overlay.hpp): cairo, with DejaVu Sans loaded from its file through FreeType (no
// fontconfig), so the same annotations on the same frame give the same bytes on every machine.
//
// Sizes follow the frame: text is min(width, height) / 45 pixels high (24 px on a 1920 × 1080
// frame, 48 on 3840 × 2160), never below 10; margins, strips and rules scale with the text. Text
// and rules are light on a dark translucent panel (dark theme) or dark on a light one, as the
// --hud panel is, so they read over any frame. Nothing is drawn outside the image.

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plot/figure.hpp"
#include "plot/ticks.hpp"

namespace particles::plot {

// A colour bar: the colormap's colours as a strip from lo (at the bottom, or the left) to hi, its
// ticks (plot/ticks.hpp: nice linear steps, or decades and their multiples on a log scale) and its
// label, on one side of the frame.
struct ColorbarSpec {
  enum class Side { right, left, top, bottom };     // the order of style::ColorbarPosition
  std::vector<std::array<std::uint8_t, 3>> colors;  // the colormap's entries, low to high (not empty)
  double lo = 0.0, hi = 1.0;                        // the values at the strip's ends (finite)
  bool logScale = false;                            // ticks for log10 of the value (then 0 < lo)
  std::string label;                                // with its unit: "speed (m/s)"
  Side side = Side::right;
};

// Text beside a point (a selected particle or body): up and to the right of (x, y), in pixels from
// the frame's top-left corner; clipped where it leaves the frame.
struct TextAt {
  double x = 0.0, y = 0.0;
  std::string text;
};

// A bar of a round length in the bottom-left corner, with its length written above it.
struct ScaleBarSpec {
  double pixelsPerMetre = 0.0;  // the camera's scale (> 0, finite)
};

struct FrameAnnotations {
  std::optional<ColorbarSpec> colorbar;
  std::string title;  // centred at the top; none when empty
  std::optional<ScaleBarSpec> scaleBar;
  std::vector<TextAt> labels;
  bool darkTheme = true;  // light text on dark panels, or dark on light
  std::filesystem::path fontFile = defaultFontFile();
};

// Draws `annotations` onto an 8-bit RGBA image (row-major, top row first, straight alpha). Where
// nothing is drawn the pixels, alpha included, are left as they are; what is drawn is composited
// over them (an opaque strip or rule makes its pixels opaque, a translucent panel adds its alpha).
// Throws FigureError naming what failed: the font file, a cairo call, or a spec out of range (a
// colour bar without colours or with lo ≥ hi, a scale bar's pixelsPerMetre ≤ 0 or not finite).
void drawFrameAnnotations(std::uint8_t* rgba, int width, int height, const FrameAnnotations& annotations);

// A rectangle of pixels: x, y of its top-left corner; empty when width or height is 0.
struct PixelBox {
  int x = 0, y = 0, width = 0, height = 0;
  bool empty() const { return width <= 0 || height <= 0; }
};

// Where drawFrameAnnotations puts each thing on a frame of this size (before clipping to it): for
// callers that place other things around them, and for the tests.
struct AnnotationLayout {
  double textPx = 0.0;                 // the height of body text
  PixelBox title;                      // the title's panel
  PixelBox colorbar;                   // the colour bar's panel
  PixelBox colorbarStrip;              // the colours: its first row (vertical) or column (horizontal) is lo's
  std::vector<Tick> colorbarTicks;     // the labelled ticks, low to high
  std::vector<double> colorbarTickPx;  // where each lies along the strip: a frame y (vertical) or x
  PixelBox scaleBar;                   // the scale bar's panel
  PixelBox scaleBarRule;               // the bar: its width is the length's pixels
  std::vector<PixelBox> labels;        // each label's panel, in the order given
};
AnnotationLayout layoutFrameAnnotations(int width, int height, const FrameAnnotations& annotations);

// A scale bar's length: the longest 1, 2 or 5 × 10^k metres that is at most a fifth of the frame's
// width, and how it is written: in the largest of nm, µm, mm, cm, m, km that leaves a whole number
// ("50 cm", "1 m", "2 km", "200 µm"), or as a power of ten of metres outside 1 nm … 10⁹ m ("5×10⁻¹² m").
struct ScaleLength {
  double metres = 0.0;
  std::string text;
};
ScaleLength scaleBarLength(double pixelsPerMetre, int frameWidth);

// The most characters (code points) an annotation shows; longer text is cut and ends in "…".
inline constexpr std::size_t kMostAnnotationCharacters = 200;

// Text as an annotation draws it: valid UTF-8 for cairo_show_text, which needs it; control
// characters and bytes that are not UTF-8 shown as escapes (input/printable_text.hpp), a line
// break or tab as a space; at most kMostAnnotationCharacters, cut with "…".
std::string annotationText(std::string_view text);

}  // namespace particles::plot
