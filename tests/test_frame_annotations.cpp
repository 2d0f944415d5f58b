// What a style draws over a frame (plot/frame_annotations.hpp): the colour bar's strip and ticks,
// the title, the scale bar and labels, checked in pixels on frames from 320 × 180 to 3840 × 2160.

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "plot/errors.hpp"
#include "plot/frame_annotations.hpp"

using namespace particles::plot;

namespace {

// A frame of one colour, with guard bytes before and after it that nothing may change.
struct GuardedFrame {
  static constexpr std::size_t kGuard = 4096;
  static constexpr std::uint8_t kGuardByte = 0xA5;
  int width, height;
  std::vector<std::uint8_t> bytes;

  GuardedFrame(int w, int h, std::array<std::uint8_t, 4> fill) : width(w), height(h) {
    bytes.assign(std::size_t(w) * std::size_t(h) * 4 + 2 * kGuard, kGuardByte);
    for (std::size_t i = 0; i < std::size_t(w) * std::size_t(h); ++i)
      std::copy(fill.begin(), fill.end(), rgba() + 4 * i);
  }
  std::uint8_t* rgba() { return bytes.data() + kGuard; }
  std::array<std::uint8_t, 4> at(int x, int y) {
    const std::uint8_t* p = rgba() + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4;
    return {p[0], p[1], p[2], p[3]};
  }
  bool guardsIntact() const {
    const auto intact = [&](std::size_t from) {
      return std::all_of(bytes.begin() + std::ptrdiff_t(from), bytes.begin() + std::ptrdiff_t(from + kGuard),
                         [](std::uint8_t b) { return b == kGuardByte; });
    };
    return intact(0) && intact(bytes.size() - kGuard);
  }
  void draw(const FrameAnnotations& a) { drawFrameAnnotations(rgba(), width, height, a); }
};

double luminance(const std::array<std::uint8_t, 4>& p) {
  return 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
}

std::array<std::uint8_t, 3> rgb(const std::array<std::uint8_t, 4>& p) {
  return {p[0], p[1], p[2]};
}

// A colormap whose every entry differs: red rising, blue falling, green marking the index's parity.
std::vector<std::array<std::uint8_t, 3>> rampColors() {
  std::vector<std::array<std::uint8_t, 3>> colors;
  for (int i = 0; i < 256; ++i) {
    colors.push_back({std::uint8_t(i), std::uint8_t(i % 2 == 0 ? 40 : 200), std::uint8_t(255 - i)});
  }
  return colors;
}

ColorbarSpec colorbarOn(ColorbarSpec::Side side, double lo = 0.0, double hi = 10.0, bool logScale = false) {
  ColorbarSpec c;
  c.colors = rampColors();
  c.lo = lo;
  c.hi = hi;
  c.logScale = logScale;
  c.label = "speed (m/s)";
  c.side = side;
  return c;
}

bool inside(const PixelBox& box, int width, int height) {
  return box.x >= 0 && box.y >= 0 && box.x + box.width <= width && box.y + box.height <= height;
}

// How many pixels of `box` (clipped to the frame) are brighter than `least` luminance.
int brightPixels(GuardedFrame& f, const PixelBox& box, double least) {
  int count = 0;
  for (int y = std::max(box.y, 0); y < std::min(box.y + box.height, f.height); ++y) {
    for (int x = std::max(box.x, 0); x < std::min(box.x + box.width, f.width); ++x)
      count += luminance(f.at(x, y)) > least;
  }
  return count;
}

constexpr std::array kSides = {ColorbarSpec::Side::right, ColorbarSpec::Side::left, ColorbarSpec::Side::top,
                               ColorbarSpec::Side::bottom};

}  // namespace

TEST_CASE("frame annotations: the strip's ends are the colormap's first and last colours, on every side") {
  const std::vector<std::array<std::uint8_t, 3>> colors = rampColors();
  for (const auto& [width, height] : {std::pair{320, 180}, std::pair{1920, 1080}}) {
    for (const ColorbarSpec::Side side : kSides) {
      CAPTURE(width);
      CAPTURE(int(side));
      FrameAnnotations a;
      a.colorbar = colorbarOn(side);
      const AnnotationLayout layout = layoutFrameAnnotations(width, height, a);
      const PixelBox& s = layout.colorbarStrip;
      REQUIRE(!s.empty());
      CHECK(inside(layout.colorbar, width, height));
      GuardedFrame f(width, height, {30, 30, 30, 255});
      f.draw(a);
      const bool vertical = side == ColorbarSpec::Side::right || side == ColorbarSpec::Side::left;
      const int length = vertical ? s.height : s.width;
      CHECK(length >= (vertical ? 0.4 * height : 0.3 * width));
      // Along the strip, j from lo's end: entry round(j · 255 / (length − 1)), across its whole thickness.
      for (const int j : {0, 1, length / 2, length - 2, length - 1}) {
        const int entry = int(std::lround(double(j) * 255 / (length - 1)));
        for (const int across : {0, (vertical ? s.width : s.height) - 1}) {
          const int x = vertical ? s.x + across : s.x + j, y = vertical ? s.y + s.height - 1 - j : s.y + across;
          CHECK_MESSAGE(rgb(f.at(x, y)) == colors[std::size_t(entry)], "j = " << j << ", entry " << entry);
          CHECK(f.at(x, y)[3] == 255);
        }
      }
      CHECK(f.guardsIntact());
    }
  }
}

TEST_CASE("frame annotations: linear ticks are nice steps from lo to hi, each with its label drawn") {
  FrameAnnotations a;
  a.colorbar = colorbarOn(ColorbarSpec::Side::right, 0.0, 10.0);
  const AnnotationLayout layout = layoutFrameAnnotations(1920, 1080, a);
  const PixelBox& s = layout.colorbarStrip;
  REQUIRE(layout.colorbarTicks.size() == layout.colorbarTickPx.size());
  // A 486-pixel strip asks for 8 ticks: linearTicks's step for 0 … 10 is then 2.
  std::vector<double> values;
  for (const Tick& t : layout.colorbarTicks) values.push_back(t.value);
  CHECK(values == std::vector<double>{0, 2, 4, 6, 8, 10});
  CHECK(layout.colorbarTicks.front().label.text == "0");
  CHECK(layout.colorbarTicks.back().label.text == "10");
  // lo at the centre of the strip's bottom row, hi at its top row's, evenly between.
  CHECK(layout.colorbarTickPx.front() == doctest::Approx(s.y + s.height - 0.5));
  CHECK(layout.colorbarTickPx.back() == doctest::Approx(s.y + 0.5));
  for (std::size_t i = 1; i < values.size(); ++i) {
    CHECK(layout.colorbarTickPx[i - 1] - layout.colorbarTickPx[i] == doctest::Approx((s.height - 1) / 5.0));
  }
  // Each label: light pixels right of its tick, on the tick's line, on a black frame (dark theme).
  GuardedFrame f(1920, 1080, {0, 0, 0, 255});
  f.draw(a);
  const int text = int(layout.textPx);
  for (const double y : layout.colorbarTickPx) {
    const PixelBox beside{s.x + s.width + text / 2, int(y) - text / 3, 3 * text / 2, 2 * (text / 3)};
    CHECK_MESSAGE(brightPixels(f, beside, 128) >= 5, "the label at y = " << y);
  }
  // Between two labels, nothing is drawn there.
  const int between = int((layout.colorbarTickPx[0] + layout.colorbarTickPx[1]) / 2);
  CHECK(brightPixels(f, PixelBox{s.x + s.width + text / 2, between - 2, 3 * text / 2, 4}, 128) == 0);
}

TEST_CASE("frame annotations: a log colour bar has its ticks on decades, evenly spaced") {
  FrameAnnotations a;
  a.colorbar = colorbarOn(ColorbarSpec::Side::bottom, 0.01, 100.0, true);
  const AnnotationLayout layout = layoutFrameAnnotations(1920, 1080, a);
  const PixelBox& s = layout.colorbarStrip;
  std::vector<double> values;
  for (const Tick& t : layout.colorbarTicks) values.push_back(t.value);
  REQUIRE(values.size() == 5);
  for (std::size_t i = 0; i < values.size(); ++i) CHECK(values[i] == doctest::Approx(std::pow(10.0, int(i) - 2)));
  CHECK(layout.colorbarTickPx.front() == doctest::Approx(s.x + 0.5));
  CHECK(layout.colorbarTickPx.back() == doctest::Approx(s.x + s.width - 0.5));
  for (std::size_t i = 1; i < values.size(); ++i) {
    CHECK(layout.colorbarTickPx[i] - layout.colorbarTickPx[i - 1] == doctest::Approx((s.width - 1) / 4.0));
  }
}

TEST_CASE("frame annotations: nothing is drawn outside the image, at 320 x 180 and at 3840 x 2160") {
  for (const auto& [width, height] : {std::pair{320, 180}, std::pair{3840, 2160}}) {
    for (const ColorbarSpec::Side side : kSides) {
      CAPTURE(width);
      CAPTURE(int(side));
      FrameAnnotations a;
      a.colorbar = colorbarOn(side, 1e-3, 5e4, side == ColorbarSpec::Side::left);
      a.colorbar->label = std::string(300, 'L');
      a.title = "A title long enough to be wider than the smallest frame, so it has to shrink to fit";
      a.scaleBar = ScaleBarSpec{width / 3.0};
      // Anchors at the corners, past them, and far away.
      for (const auto& [x, y] :
           {std::pair{0.0, 0.0}, std::pair{double(width), double(height)}, std::pair{width - 3.0, 3.0},
            std::pair{-50.0, height / 2.0}, std::pair{1e300, -1e300}}) {
        a.labels.push_back({x, y, "label at the edge"});
      }
      const AnnotationLayout layout = layoutFrameAnnotations(width, height, a);
      CHECK(inside(layout.colorbar, width, height));
      CHECK(inside(layout.title, width, height));
      CHECK(inside(layout.scaleBar, width, height));
      CHECK(layout.labels.size() == a.labels.size());
      CHECK(layout.labels.back().empty());  // far away: not drawn
      GuardedFrame f(width, height, {90, 90, 90, 255});
      f.draw(a);
      CHECK(f.guardsIntact());
    }
  }
}

TEST_CASE("frame annotations: text is sized by the frame, 10 px at least") {
  FrameAnnotations a;
  a.title = "t";
  CHECK(layoutFrameAnnotations(320, 180, a).textPx == 10);
  CHECK(layoutFrameAnnotations(1920, 1080, a).textPx == 24);
  CHECK(layoutFrameAnnotations(3840, 2160, a).textPx == 48);
  CHECK(layoutFrameAnnotations(1080, 1920, a).textPx == 24);  // portrait: by the width
}

TEST_CASE("frame annotations: text stands out from its panel on the dark and the light theme") {
  for (const bool dark : {true, false}) {
    for (const std::uint8_t background : {std::uint8_t(0), std::uint8_t(128), std::uint8_t(255)}) {
      CAPTURE(dark);
      CAPTURE(int(background));
      FrameAnnotations a;
      a.darkTheme = dark;
      a.title = "Energy";
      const AnnotationLayout layout = layoutFrameAnnotations(1280, 720, a);
      GuardedFrame f(1280, 720, {background, background, background, 255});
      f.draw(a);
      const PixelBox& p = layout.title;
      const double panel = luminance(f.at(p.x + 1, p.y + 1));
      double farthest = 0;  // the text's pixel farthest from the panel in luminance
      for (int y = p.y; y < p.y + p.height; ++y) {
        for (int x = p.x; x < p.x + p.width; ++x)
          farthest = std::max(farthest, std::fabs(luminance(f.at(x, y)) - panel));
      }
      CHECK(farthest >= 120);
      // The panel darkens (dark theme) or lightens (light theme) the frame behind it.
      CHECK((dark ? panel <= background * 0.45 : panel >= 0.6 * 255 - 1));
    }
  }
}

TEST_CASE("frame annotations: the scale bar is a round length, and that many pixels long") {
  struct Case {
    double pixelsPerMetre;
    int width;
    double metres;
    const char* text;
  };
  for (const Case& c : {Case{1000, 1920, 0.2, "20 cm"}, Case{100, 1920, 2, "2 m"}, Case{100, 500, 1, "1 m"},
                        Case{400, 1000, 0.5, "50 cm"}, Case{1, 1000, 200, "200 m"}, Case{0.01, 1000, 2e4, "20 km"},
                        Case{1e-6, 1000, 2e8, "200000 km"}, Case{1e4, 1000, 0.02, "2 cm"},
                        Case{1e5, 1000, 2e-3, "2 mm"}, Case{1e8, 1000, 2e-6, "2 \u00b5m"},
                        Case{1e11, 1000, 2e-9, "2 nm"}, Case{1e13, 1000, 2e-11, "2\u00d710\u207b\u00b9\u00b9 m"},
                        Case{1e-9, 1000, 2e11, "2\u00d710\u00b9\u00b9 m"}, Case{3.7, 320, 10, "10 m"}}) {
    CAPTURE(c.pixelsPerMetre);
    const ScaleLength length = scaleBarLength(c.pixelsPerMetre, c.width);
    CHECK(length.metres == doctest::Approx(c.metres));
    CHECK(length.text == c.text);
    CHECK(length.metres * c.pixelsPerMetre <= c.width / 5.0 * (1 + 1e-12));
    CHECK(length.metres * c.pixelsPerMetre > c.width / 5.0 / 2.5);
  }
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) CHECK_THROWS_AS(scaleBarLength(bad, 1000), FigureError);

  for (const bool dark : {true, false}) {
    FrameAnnotations a;
    a.darkTheme = dark;
    a.scaleBar = ScaleBarSpec{377.0};  // 1920 / 5 / 377 = 1.02 m: a 1 m bar, 377 px
    const AnnotationLayout layout = layoutFrameAnnotations(1920, 1080, a);
    const PixelBox& rule = layout.scaleBarRule;
    CHECK(rule.width == 377);
    CHECK(inside(layout.scaleBar, 1920, 1080));
    GuardedFrame f(1920, 1080, {128, 128, 128, 255});
    f.draw(a);
    const std::uint8_t ink = dark ? 235 : 25;
    int inked = 0;  // along the bar's middle row, across the whole frame
    for (int x = 0; x < 1920; ++x)
      inked += f.at(x, rule.y + rule.height / 2) == std::array<std::uint8_t, 4>{ink, ink, ink, 255};
    CHECK(std::abs(inked - 377) <= 1);
  }
}

TEST_CASE("frame annotations: text is made printable and bounded") {
  CHECK(annotationText("bob") == "bob");
  CHECK(annotationText("a\x1b[31mb") == "a\\x1b[31mb");
  CHECK(annotationText("\xff\xfe ok \xc3") == "\\xff\\xfe ok \\xc3");
  CHECK(annotationText("two\nlines\tand a tab") == "two lines and a tab");
  CHECK(annotationText("\xc3\xa9t\xc3\xa9") == "\xc3\xa9t\xc3\xa9");  // été stays
  const std::string exactly(kMostAnnotationCharacters, 'x');
  CHECK(annotationText(exactly) == exactly);
  CHECK(annotationText(std::string(10000, 'x')) == std::string(kMostAnnotationCharacters - 1, 'x') + "\u2026");
  std::string accents;
  for (int i = 0; i < 300; ++i) accents += "\xc3\xa9";
  CHECK(annotationText(accents) == accents.substr(0, 2 * (kMostAnnotationCharacters - 1)) + "\u2026");
}

TEST_CASE("frame annotations: a hostile label draws without error, and its panel is bounded") {
  std::string hostile = "\xff\x01\x1b]0;title\x07\xc3(\xe2\x82\n";
  hostile += std::string(10000, 'W');
  FrameAnnotations a;
  a.labels.push_back({100, 500, hostile});
  a.title = hostile;
  a.colorbar = colorbarOn(ColorbarSpec::Side::right);
  a.colorbar->label = hostile;
  const AnnotationLayout layout = layoutFrameAnnotations(1280, 720, a);
  REQUIRE(layout.labels.size() == 1);
  // 200 characters at most, none wider than the text is high ("W" is the widest ASCII letter).
  CHECK(layout.labels[0].width <= int(kMostAnnotationCharacters * layout.textPx));
  CHECK(inside(layout.title, 1280, 720));
  GuardedFrame f(1280, 720, {0, 0, 0, 255});
  CHECK_NOTHROW(f.draw(a));
  CHECK(f.guardsIntact());
}

TEST_CASE("frame annotations: a transparent frame stays transparent where nothing is drawn") {
  FrameAnnotations a;
  a.labels.push_back({600, 400, "bob"});
  a.colorbar = colorbarOn(ColorbarSpec::Side::right);
  const AnnotationLayout layout = layoutFrameAnnotations(1280, 720, a);
  GuardedFrame f(1280, 720, {0, 0, 0, 0});
  f.draw(a);
  const PixelBox& label = layout.labels[0];
  const PixelBox& bar = layout.colorbar;
  const auto within = [](const PixelBox& b, int x, int y) {
    return x >= b.x && x < b.x + b.width && y >= b.y && y < b.y + b.height;
  };
  int changed = 0;
  for (int y = 0; y < 720; ++y) {
    for (int x = 0; x < 1280; ++x) {
      if (within(label, x, y) || within(bar, x, y)) continue;
      changed += f.at(x, y) != std::array<std::uint8_t, 4>{0, 0, 0, 0};
    }
  }
  CHECK(changed == 0);
  // The panel is translucent (the --hud panel's 60 %), the strip opaque.
  CHECK(int(f.at(label.x + 1, label.y + 1)[3]) == 153);
  CHECK(int(f.at(layout.colorbarStrip.x + 2, layout.colorbarStrip.y + 2)[3]) == 255);
}

TEST_CASE("frame annotations: the same annotations draw the same bytes") {
  FrameAnnotations a;
  a.title = "Same";
  a.colorbar = colorbarOn(ColorbarSpec::Side::top, 1, 1000, true);
  a.scaleBar = ScaleBarSpec{50};
  a.labels.push_back({300, 300, "p"});
  GuardedFrame first(640, 360, {10, 20, 30, 255}), second(640, 360, {10, 20, 30, 255});
  first.draw(a);
  second.draw(a);
  CHECK(first.bytes == second.bytes);
}

TEST_CASE("frame annotations: errors name what failed") {
  GuardedFrame f(320, 180, {0, 0, 0, 255});
  FrameAnnotations a;
  a.colorbar = colorbarOn(ColorbarSpec::Side::right);
  a.colorbar->colors.clear();
  CHECK_THROWS_WITH_AS(f.draw(a), doctest::Contains("no colours"), FigureError);
  a.colorbar = colorbarOn(ColorbarSpec::Side::right, 2.0, 2.0);
  CHECK_THROWS_WITH_AS(f.draw(a), doctest::Contains("range [2, 2]"), FigureError);
  a.colorbar = colorbarOn(ColorbarSpec::Side::right, 0.0, 1.0, true);
  CHECK_THROWS_WITH_AS(f.draw(a), doctest::Contains("lo > 0 on a log scale"), FigureError);
  a.colorbar.reset();
  a.scaleBar = ScaleBarSpec{-2};
  CHECK_THROWS_WITH_AS(f.draw(a), doctest::Contains("scale bar"), FigureError);
  a.scaleBar.reset();
  a.title = "t";
  a.fontFile = "/nonexistent/NoSuchFont.ttf";
  CHECK_THROWS_WITH_AS(f.draw(a), doctest::Contains("/nonexistent/NoSuchFont.ttf"), FigureError);
  CHECK_THROWS_AS(drawFrameAnnotations(nullptr, 10, 10, a), FigureError);
  CHECK_NOTHROW(drawFrameAnnotations(nullptr, 0, 0, a));  // nothing to draw on, nothing drawn
}
