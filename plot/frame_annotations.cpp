#include "plot/frame_annotations.hpp"

#include <cairo.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "input/printable_text.hpp"
#include "plot/annotation_layer.hpp"
#include "plot/errors.hpp"
#include "plot/font.hpp"

namespace particles::plot {

namespace {

// Sizes in pixels, from the text's height (frame_annotations.hpp): margins from the frame's edges,
// padding inside a panel, gaps between its parts, line widths, the strip's thickness, a tick mark.
struct Sizes {
  double text;
  int margin, pad, gap, line, strip, tick;
};

Sizes sizesFor(int width, int height) {
  const double text = std::max(10.0, std::round(std::min(width, height) / 45.0));
  const auto px = [&](double share, int least) { return std::max(least, static_cast<int>(std::lround(share * text))); };
  return {text, px(0.8, 4), px(0.4, 2), px(0.25, 2), px(1.0 / 12, 1), px(0.9, 8), px(0.35, 3)};
}

// A box's coordinate from a double that may lie far outside any frame (a label's anchor).
int pixelOf(double v) {
  return static_cast<int>(std::lround(std::clamp(v, -1e7, 1e7)));
}

// The colour bar, laid out: the public boxes and ticks, and where its text goes.
struct ColorbarPlan {
  PixelBox panel, strip;
  AxisTicks axis;
  std::vector<double> tickPx, minorPx;  // along the strip, frame coordinates
  double tickTextPx = 0, labelPx = 0;   // text sizes
  double maxTickWidth = 0;
  std::string label;
  bool vertical = true;
};

struct TextPlan {
  PixelBox panel;
  std::string text;
  double sizePx = 0;
};

struct ScaleBarPlan {
  PixelBox panel, rule;
  ScaleLength length;
  double sizePx = 0;
};

struct Plan {
  Sizes sizes{};
  std::optional<TextPlan> title;
  std::optional<ColorbarPlan> colorbar;
  std::optional<ScaleBarPlan> scaleBar;
  std::vector<std::optional<TextPlan>> labels;
};

void checkColorbar(const ColorbarSpec& c) {
  if (c.colors.empty()) throw FigureError("frame annotations: the colour bar has no colours");
  if (!std::isfinite(c.lo) || !std::isfinite(c.hi) || !(c.lo < c.hi) || (c.logScale && !(c.lo > 0))) {
    throw FigureError(fmt::format("frame annotations: the colour bar's range [{}, {}] is not finite and increasing{}",
                                  c.lo, c.hi, c.logScale ? ", with lo > 0 on a log scale" : ""));
  }
}

// The ticks along a strip `lengthPx` long: about one per 2.5 lines of tick text along a vertical
// strip, one per 6 text heights (a label's width) along a horizontal one, 3 to 8 asked for (a
// linear axis asked for 2 gets one step over the whole range: often a tick at lo alone).
AxisTicks colorbarAxis(const ColorbarSpec& c, double lengthPx, double tickTextPx, bool vertical) {
  const int target = std::clamp(static_cast<int>(lengthPx / ((vertical ? 2.5 : 6.0) * tickTextPx)), 3, 8);
  AxisTicks axis = c.logScale ? logTicksWithin(c.lo, c.hi, target) : linearTicks(c.lo, c.hi, target, false);
  // The strip shows [lo, hi], also where linearTicks widens a range too narrow to label.
  axis.lo = c.lo;
  axis.hi = c.hi;
  return axis;
}

// Where a value lies along the colour bar: 0 at lo, 1 at hi, on its scale.
double colorbarFraction(double v, const AxisTicks& axis, bool logScale) {
  if (!logScale) return axisFraction(v, axis);
  return (std::log10(v) - std::log10(axis.lo)) / (std::log10(axis.hi) - std::log10(axis.lo));
}

// The strip's pixel centres carry the values: lo at the first row (from the bottom) or column,
// hi at the last, so that their colours are the colormap's first and last.
void placeTicks(ColorbarPlan& bar, bool logScale) {
  const PixelBox& s = bar.strip;
  const auto at = [&](double v) {
    const double f = colorbarFraction(v, bar.axis, logScale);
    return bar.vertical ? s.y + s.height - 0.5 - f * (s.height - 1) : s.x + 0.5 + f * (s.width - 1);
  };
  const auto inside = [&](double v) {
    const double f = colorbarFraction(v, bar.axis, logScale);
    return f >= -1e-9 && f <= 1 + 1e-9;
  };
  std::vector<Tick> kept;
  for (const Tick& t : bar.axis.major) {
    if (!inside(t.value)) continue;
    kept.push_back(t);
    bar.tickPx.push_back(at(t.value));
  }
  bar.axis.major = std::move(kept);
  for (double v : bar.axis.minor) {
    if (inside(v)) bar.minorPx.push_back(at(v));
  }
}

double widestTick(const Typesetter& type, const AxisTicks& axis, double sizePx) {
  double widest = 0;
  for (const Tick& t : axis.major) widest = std::max(widest, type.advance(t.label, sizePx));
  return widest;
}

ColorbarPlan planColorbar(const Typesetter& type, const Sizes& z, int width, int height, const ColorbarSpec& c,
                          const std::optional<TextPlan>& title) {
  checkColorbar(c);
  ColorbarPlan bar;
  bar.vertical = c.side == ColorbarSpec::Side::right || c.side == ColorbarSpec::Side::left;
  bar.tickTextPx = 0.85 * z.text;
  bar.label = annotationText(c.label);
  const double tickLine = type.lineHeight(bar.tickTextPx);
  const int tickOverhang = static_cast<int>(std::ceil(tickLine / 2));  // an end tick's label past the strip
  if (bar.vertical) {
    const int room = height - 2 * z.margin - 2 * z.pad - 2 * tickOverhang;
    const int length = std::max(2, std::min(static_cast<int>(std::lround(0.45 * height)), room));
    bar.axis = colorbarAxis(c, length, bar.tickTextPx, true);
    bar.maxTickWidth = widestTick(type, bar.axis, bar.tickTextPx);
    bar.labelPx = bar.label.empty() ? 0 : type.fit(bar.label, z.text, length + 2.0 * tickOverhang);
    const int labelRoom = bar.label.empty() ? 0 : 2 * z.gap + static_cast<int>(std::ceil(type.lineHeight(bar.labelPx)));
    const int panelW =
        2 * z.pad + z.strip + z.line + z.tick + z.gap + static_cast<int>(std::ceil(bar.maxTickWidth)) + labelRoom;
    const int panelH = length + 2 * z.pad + 2 * tickOverhang;
    const int x = c.side == ColorbarSpec::Side::right ? width - z.margin - panelW : z.margin;
    bar.panel = {x, (height - panelH) / 2, panelW, panelH};
    bar.strip = {x + z.pad, bar.panel.y + z.pad + tickOverhang, z.strip, length};
  } else {
    const int room = width - 2 * z.margin - 2 * z.pad;
    int length = std::max(2, std::min(static_cast<int>(std::lround(0.4 * width)), room));
    bar.axis = colorbarAxis(c, length, bar.tickTextPx, false);
    bar.maxTickWidth = widestTick(type, bar.axis, bar.tickTextPx);
    const int overhang = static_cast<int>(std::ceil(bar.maxTickWidth / 2));
    if (length > room - 2 * overhang) {
      length = std::max(2, room - 2 * overhang);
      bar.axis = colorbarAxis(c, length, bar.tickTextPx, false);
    }
    bar.labelPx = bar.label.empty() ? 0 : type.fit(bar.label, z.text, room);
    const int labelW =  // clipped by the panel where even the smallest size is too wide
        bar.label.empty() ? 0 : std::min(room, static_cast<int>(std::ceil(type.advance(bar.label, bar.labelPx))));
    const int labelRoom = bar.label.empty() ? 0 : static_cast<int>(std::ceil(type.lineHeight(bar.labelPx))) + z.gap;
    const int panelW = 2 * z.pad + std::max(length + 2 * overhang, labelW);
    const int panelH =
        2 * z.pad + labelRoom + z.strip + z.line + z.tick + z.gap + static_cast<int>(std::ceil(tickLine));
    const int top = title ? title->panel.y + title->panel.height + z.gap : z.margin;
    const int y = c.side == ColorbarSpec::Side::bottom ? height - z.margin - panelH : top;
    bar.panel = {(width - panelW) / 2, y, panelW, panelH};
    bar.strip = {bar.panel.x + (panelW - length) / 2, y + z.pad + labelRoom, length, z.strip};
  }
  placeTicks(bar, c.logScale);
  return bar;
}

TextPlan planTitle(const Typesetter& type, const Sizes& z, int width, const std::string& title) {
  TextPlan plan;
  plan.text = annotationText(title);
  plan.sizePx = type.fit(plan.text, 1.25 * z.text, width - 2.0 * (z.margin + z.pad));
  // Clipped by its panel where even the smallest size is too wide.
  const int w =
      std::min(static_cast<int>(std::ceil(type.advance(plan.text, plan.sizePx))) + 2 * z.pad, width - 2 * z.margin);
  const int h = static_cast<int>(std::ceil(type.lineHeight(plan.sizePx))) + 2 * z.pad;
  plan.panel = {(width - w) / 2, z.margin, w, h};
  return plan;
}

ScaleBarPlan planScaleBar(const Typesetter& type, const Sizes& z, int width, int height, const ScaleBarSpec& s) {
  ScaleBarPlan plan;
  plan.length = scaleBarLength(s.pixelsPerMetre, width);
  plan.sizePx = 0.9 * z.text;
  const int rulePx = std::max(1, static_cast<int>(std::lround(plan.length.metres * s.pixelsPerMetre)));
  const int ruleH = std::max(2, static_cast<int>(std::lround(0.25 * z.text)));
  const int textW = static_cast<int>(std::ceil(type.advance(plan.length.text, plan.sizePx)));
  const int w = 2 * z.pad + std::max(rulePx, textW);
  const int h = 2 * z.pad + static_cast<int>(std::ceil(type.lineHeight(plan.sizePx))) + z.gap + ruleH;
  plan.panel = {z.margin, height - z.margin - h, w, h};
  plan.rule = {z.margin + z.pad, plan.panel.y + h - z.pad - ruleH, rulePx, ruleH};
  return plan;
}

std::optional<TextPlan> planLabel(const Typesetter& type, const Sizes& z, int width, int height, const TextAt& at) {
  if (!std::isfinite(at.x) || !std::isfinite(at.y) || at.text.empty()) return std::nullopt;
  TextPlan plan;
  plan.text = annotationText(at.text);
  plan.sizePx = 0.9 * z.text;
  const int inset = std::max(2, z.pad / 2), offset = static_cast<int>(std::lround(0.3 * z.text));
  const int w = static_cast<int>(std::ceil(type.advance(plan.text, plan.sizePx))) + 2 * inset;
  const int h = static_cast<int>(std::ceil(type.lineHeight(plan.sizePx))) + 2 * inset;
  plan.panel = {pixelOf(at.x) + offset, pixelOf(at.y) - offset - h, w, h};
  const bool outside =
      plan.panel.x >= width || plan.panel.y >= height || plan.panel.x + w <= 0 || plan.panel.y + h <= 0;
  if (outside) return std::nullopt;
  return plan;
}

Plan plan(const Typesetter& type, int width, int height, const FrameAnnotations& a) {
  Plan p;
  p.sizes = sizesFor(width, height);
  if (!a.title.empty()) p.title = planTitle(type, p.sizes, width, a.title);
  if (a.colorbar) p.colorbar = planColorbar(type, p.sizes, width, height, *a.colorbar, p.title);
  if (a.scaleBar) p.scaleBar = planScaleBar(type, p.sizes, width, height, *a.scaleBar);
  for (const TextAt& label : a.labels) p.labels.push_back(planLabel(type, p.sizes, width, height, label));
  return p;
}

// The strip's pixels, written as they are (opaque, no filtering): row j from the bottom (column j
// from the left) takes entry round(j / (L − 1) · (N − 1)), so the ends are the first and last.
void fillStrip(Layer& layer, const ColorbarPlan& bar, const std::vector<std::array<std::uint8_t, 3>>& colors) {
  const PixelBox& s = bar.strip;
  const int length = bar.vertical ? s.height : s.width;
  const int last = static_cast<int>(colors.size()) - 1;
  for (int y = 0; y < s.height; ++y) {
    for (int x = 0; x < s.width; ++x) {
      const int j = bar.vertical ? s.height - 1 - y : x;
      const int entry = length > 1 ? static_cast<int>(std::lround(double(j) * last / (length - 1))) : 0;
      const auto& rgb = colors[static_cast<std::size_t>(entry)];
      layer.setOpaque(s.x + x, s.y + y, rgb[0], rgb[1], rgb[2]);
    }
  }
}

void drawColorbar(Layer& layer, const Typesetter& type, const Sizes& z, const ColorbarPlan& bar,
                  const ColorbarSpec& spec) {
  cairo_t* cr = layer.cr();
  const PixelBox& s = bar.strip;
  const double lw = z.line;
  cairo_set_line_width(cr, lw);
  cairo_rectangle(cr, s.x - lw / 2, s.y - lw / 2, s.width + lw, s.height + lw);
  cairo_stroke(cr);
  const double edge = bar.vertical ? s.x + s.width + lw : s.y + s.height + lw;  // ticks start past the outline
  const auto mark = [&](double at, double length) {
    if (bar.vertical) {
      cairo_move_to(cr, edge, at);
      cairo_line_to(cr, edge + length, at);
    } else {
      cairo_move_to(cr, at, edge);
      cairo_line_to(cr, at, edge + length);
    }
  };
  for (double at : bar.tickPx) mark(at, z.tick);
  for (double at : bar.minorPx) mark(at, 0.6 * z.tick);
  cairo_stroke(cr);
  const double labelsAt = edge + z.tick + z.gap;
  for (std::size_t i = 0; i < bar.tickPx.size(); ++i) {
    const Label& label = bar.axis.major[i].label;
    if (bar.vertical) {
      type.show(cr, label, labelsAt, bar.tickPx[i] + type.middleToBaseline(bar.tickTextPx), bar.tickTextPx);
    } else {
      const double w = type.advance(label, bar.tickTextPx);
      type.show(cr, label, bar.tickPx[i] - w / 2, labelsAt + type.ascent(bar.tickTextPx), bar.tickTextPx);
    }
  }
  if (!bar.label.empty()) {
    const double w = type.advance(bar.label, bar.labelPx);
    if (bar.vertical) {  // along the strip, read from the bottom up, past the tick labels
      const double x = labelsAt + bar.maxTickWidth + 2 * z.gap + type.lineHeight(bar.labelPx) / 2;
      cairo_save(cr);
      cairo_translate(cr, x, s.y + s.height / 2.0);
      cairo_rotate(cr, -std::numbers::pi / 2);
      type.show(cr, Label{bar.label, ""}, -w / 2, type.middleToBaseline(bar.labelPx), bar.labelPx);
      cairo_restore(cr);
    } else {
      const double y = s.y - lw - z.gap - type.descent(bar.labelPx);
      type.show(cr, Label{bar.label, ""}, s.x + s.width / 2.0 - w / 2, y, bar.labelPx);
    }
  }
  fillStrip(layer, bar, spec.colors);
}

void drawScaleBar(Layer& layer, const Typesetter& type, const Sizes& z, const ScaleBarPlan& bar) {
  cairo_t* cr = layer.cr();
  const PixelBox& r = bar.rule;
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_NONE);  // whole pixels: the bar's pixels are its length
  cairo_rectangle(cr, r.x, r.y, r.width, r.height);
  cairo_fill(cr);
  cairo_set_antialias(cr, CAIRO_ANTIALIAS_DEFAULT);
  const double x = r.x + std::max(0.0, (r.width - type.advance(bar.length.text, bar.sizePx)) / 2);
  type.show(cr, Label{bar.length.text, ""}, x, r.y - z.gap - type.descent(bar.sizePx), bar.sizePx);
}

void drawText(Layer& layer, const Typesetter& type, const TextPlan& text) {
  const double inset = (text.panel.height - type.lineHeight(text.sizePx)) / 2;
  type.show(layer.cr(), Label{text.text, ""}, text.panel.x + inset, text.panel.y + inset + type.ascent(text.sizePx),
            text.sizePx);
}

// A length of mantissa × 10^exponent metres (mantissa 1, 2 or 5) as the scale bar writes it.
std::string lengthText(int mantissa, int exponent) {
  struct Unit {
    int exponent;
    const char* name;
  };
  constexpr Unit kUnits[] = {{3, "km"}, {0, "m"}, {-2, "cm"}, {-3, "mm"}, {-6, "\u00b5m"}, {-9, "nm"}};
  if (exponent >= -9 && exponent < 9) {
    for (const Unit& unit : kUnits) {
      if (exponent < unit.exponent) continue;
      long value = mantissa;
      for (int k = unit.exponent; k < exponent; ++k) value *= 10;
      return fmt::format("{} {}", value, unit.name);
    }
  }
  // Outside 1 nm … 10⁹ m: a power of ten, in superscript digits (DejaVu Sans has them).
  constexpr const char* kSuperscripts[] = {"\u2070", "\u00b9", "\u00b2", "\u00b3", "\u2074",
                                           "\u2075", "\u2076", "\u2077", "\u2078", "\u2079"};
  std::string power = exponent < 0 ? "\u207b" : "";
  for (const char digit : std::to_string(std::abs(exponent))) power += kSuperscripts[digit - '0'];
  return fmt::format("{}\u00d710{} m", mantissa, power);
}

}  // namespace

void drawFrameAnnotations(std::uint8_t* rgba, int width, int height, const FrameAnnotations& a) {
  if (width <= 0 || height <= 0) return;
  if (!a.colorbar && a.title.empty() && !a.scaleBar && a.labels.empty()) return;
  if (rgba == nullptr) throw FigureError("frame annotations: no image to draw on");
  const FontFace font = loadAnnotationFont(a.fontFile);
  const Typesetter type(font.get());
  const Plan p = plan(type, width, height, a);
  const PanelInk ink = panelInk(a.darkTheme);
  for (const std::optional<TextPlan>& label : p.labels) {
    if (!label) continue;
    Layer layer(label->panel, width, height, ink, font.get());
    drawText(layer, type, *label);
    layer.composite(rgba, width);
  }
  if (p.title) {
    Layer layer(p.title->panel, width, height, ink, font.get());
    drawText(layer, type, *p.title);
    layer.composite(rgba, width);
  }
  if (p.scaleBar) {
    Layer layer(p.scaleBar->panel, width, height, ink, font.get());
    drawScaleBar(layer, type, p.sizes, *p.scaleBar);
    layer.composite(rgba, width);
  }
  if (p.colorbar) {
    Layer layer(p.colorbar->panel, width, height, ink, font.get());
    drawColorbar(layer, type, p.sizes, *p.colorbar, *a.colorbar);
    layer.composite(rgba, width);
  }
}

AnnotationLayout layoutFrameAnnotations(int width, int height, const FrameAnnotations& a) {
  AnnotationLayout layout;
  if (width <= 0 || height <= 0) return layout;
  const FontFace font = loadAnnotationFont(a.fontFile);
  const Typesetter type(font.get());
  const Plan p = plan(type, width, height, a);
  layout.textPx = p.sizes.text;
  if (p.title) layout.title = p.title->panel;
  if (p.colorbar) {
    layout.colorbar = p.colorbar->panel;
    layout.colorbarStrip = p.colorbar->strip;
    layout.colorbarTicks = p.colorbar->axis.major;
    layout.colorbarTickPx = p.colorbar->tickPx;
  }
  if (p.scaleBar) {
    layout.scaleBar = p.scaleBar->panel;
    layout.scaleBarRule = p.scaleBar->rule;
  }
  for (const auto& label : p.labels) layout.labels.push_back(label ? label->panel : PixelBox{});
  return layout;
}

ScaleLength scaleBarLength(double pixelsPerMetre, int frameWidth) {
  if (!std::isfinite(pixelsPerMetre) || !(pixelsPerMetre > 0) || frameWidth <= 0) {
    throw FigureError(
        fmt::format("frame annotations: the scale bar needs a positive, finite scale on a frame of some "
                    "width, not {} pixels per metre on {} pixels",
                    pixelsPerMetre, frameWidth));
  }
  const double target = frameWidth / 5.0 / pixelsPerMetre;  // metres
  // The decade 10^exponent ≤ target < 10^(exponent + 1); log10 may round across an exact power.
  int exponent = static_cast<int>(std::floor(std::log10(target)));
  if (std::pow(10.0, exponent) > target) --exponent;
  if (std::pow(10.0, exponent + 1) <= target) ++exponent;
  const double decade = std::pow(10.0, exponent);
  const int mantissa = 5 * decade <= target ? 5 : 2 * decade <= target ? 2 : 1;
  return {mantissa * decade, lengthText(mantissa, exponent)};
}

std::string annotationText(std::string_view text) {
  // A character is at most 4 bytes and printableText never shortens: the first
  // 4 · (kMostAnnotationCharacters + 1) bytes give every character kept, and tell whether more follow.
  const std::string printable = input::printableText(text.substr(0, 4 * (kMostAnnotationCharacters + 1)));
  const auto starts = [&](std::size_t i) { return (static_cast<unsigned char>(printable[i]) & 0xC0u) != 0x80u; };
  std::size_t characters = 0, cut = printable.size();  // cut: where the kept part ends, with room for "…"
  for (std::size_t i = 0; i < printable.size(); ++i) {
    if (!starts(i)) continue;
    if (++characters == kMostAnnotationCharacters) cut = i;
  }
  const bool tooLong = characters > kMostAnnotationCharacters;
  std::string out = printable.substr(0, tooLong ? cut : printable.size());
  std::replace_if(
      out.begin(), out.end(), [](char c) { return c == '\n' || c == '\t'; }, ' ');
  if (tooLong) out += "\u2026";
  return out;
}

}  // namespace particles::plot
