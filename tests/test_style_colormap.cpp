// Colormaps and colours (src/style/colormap.hpp, src/style/color.hpp). The expected 8-bit colours
// are matplotlib 3.6's `matplotlib.colormaps[name](t, bytes=True)`, taken once and written here; the
// tables themselves are checked against matplotlib, whole, by the ctest style:colormap-tables
// (tests/style/check_colormaps.py).

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "style/color.hpp"
#include "style/colormap.hpp"

using namespace particles::style;

namespace {

struct MatplotlibSample {
  const char* name;  // a colormap's name, `_r` included
  double t;
  std::array<int, 3> rgb;  // matplotlib's bytes=True
};

// ~20 values of t per map: the ends, beyond them, each side of the first and last entries' edges
// (1/256 and 255/256, and the double just below each), each side of 0.5, and values between.
constexpr MatplotlibSample kMatplotlibSamples[] = {
    {"viridis", -0.5, {68, 1, 84}},
    {"viridis", 0.0, {68, 1, 84}},
    {"viridis", 0.0039062499999999996, {68, 1, 84}},
    {"viridis", 0.00390625, {68, 2, 85}},
    {"viridis", 0.1, {72, 35, 116}},
    {"viridis", 0.2, {64, 67, 135}},
    {"viridis", 0.25, {58, 82, 139}},
    {"viridis", 0.3333333333333333, {48, 103, 141}},
    {"viridis", 0.4, {41, 120, 142}},
    {"viridis", 0.49999999999999994, {32, 143, 140}},
    {"viridis", 0.5, {32, 144, 140}},
    {"viridis", 0.6, {34, 167, 132}},
    {"viridis", 0.6666666666666666, {53, 183, 120}},
    {"viridis", 0.75, {94, 201, 97}},
    {"viridis", 0.8, {121, 209, 81}},
    {"viridis", 0.9, {189, 222, 38}},
    {"viridis", 0.9960937499999999, {250, 230, 34}},
    {"viridis", 0.99609375, {253, 231, 36}},
    {"viridis", 1.0, {253, 231, 36}},
    {"viridis", 1.5, {253, 231, 36}},
    {"magma", -0.5, {0, 0, 3}},
    {"magma", 0.0, {0, 0, 3}},
    {"magma", 0.0039062499999999996, {0, 0, 3}},
    {"magma", 0.00390625, {0, 0, 4}},
    {"magma", 0.1, {20, 13, 53}},
    {"magma", 0.2, {59, 15, 111}},
    {"magma", 0.25, {80, 18, 123}},
    {"magma", 0.3333333333333333, {113, 31, 129}},
    {"magma", 0.4, {140, 41, 128}},
    {"magma", 0.49999999999999994, {181, 54, 121}},
    {"magma", 0.5, {182, 54, 121}},
    {"magma", 0.6, {221, 73, 104}},
    {"magma", 0.6666666666666666, {240, 96, 93}},
    {"magma", 0.75, {251, 136, 97}},
    {"magma", 0.8, {253, 159, 108}},
    {"magma", 0.9, {253, 207, 146}},
    {"magma", 0.9960937499999999, {251, 250, 189}},
    {"magma", 0.99609375, {251, 252, 191}},
    {"magma", 1.0, {251, 252, 191}},
    {"magma", 1.5, {251, 252, 191}},
    {"inferno", -0.5, {0, 0, 3}},
    {"inferno", 0.0, {0, 0, 3}},
    {"inferno", 0.0039062499999999996, {0, 0, 3}},
    {"inferno", 0.00390625, {0, 0, 4}},
    {"inferno", 0.1, {22, 11, 57}},
    {"inferno", 0.2, {65, 9, 103}},
    {"inferno", 0.25, {87, 15, 109}},
    {"inferno", 0.3333333333333333, {120, 28, 109}},
    {"inferno", 0.4, {147, 37, 103}},
    {"inferno", 0.49999999999999994, {186, 54, 85}},
    {"inferno", 0.5, {187, 55, 84}},
    {"inferno", 0.6, {220, 80, 57}},
    {"inferno", 0.6666666666666666, {237, 104, 37}},
    {"inferno", 0.75, {249, 142, 8}},
    {"inferno", 0.8, {251, 164, 10}},
    {"inferno", 0.9, {245, 215, 69}},
    {"inferno", 0.9960937499999999, {250, 253, 160}},
    {"inferno", 0.99609375, {252, 254, 164}},
    {"inferno", 1.0, {252, 254, 164}},
    {"inferno", 1.5, {252, 254, 164}},
    {"plasma", -0.5, {12, 7, 134}},
    {"plasma", 0.0, {12, 7, 134}},
    {"plasma", 0.0039062499999999996, {12, 7, 134}},
    {"plasma", 0.00390625, {16, 7, 135}},
    {"plasma", 0.1, {64, 3, 156}},
    {"plasma", 0.2, {106, 0, 167}},
    {"plasma", 0.25, {126, 3, 167}},
    {"plasma", 0.3333333333333333, {155, 23, 158}},
    {"plasma", 0.4, {176, 42, 143}},
    {"plasma", 0.49999999999999994, {202, 70, 120}},
    {"plasma", 0.5, {203, 71, 119}},
    {"plasma", 0.6, {224, 100, 97}},
    {"plasma", 0.6666666666666666, {236, 120, 83}},
    {"plasma", 0.75, {248, 149, 64}},
    {"plasma", 0.8, {252, 166, 53}},
    {"plasma", 0.9, {252, 206, 37}},
    {"plasma", 0.9960937499999999, {240, 246, 35}},
    {"plasma", 0.99609375, {239, 248, 33}},
    {"plasma", 1.0, {239, 248, 33}},
    {"plasma", 1.5, {239, 248, 33}},
    {"cividis", -0.5, {0, 34, 77}},
    {"cividis", 0.0, {0, 34, 77}},
    {"cividis", 0.0039062499999999996, {0, 34, 77}},
    {"cividis", 0.00390625, {0, 35, 79}},
    {"cividis", 0.1, {8, 51, 112}},
    {"cividis", 0.2, {53, 69, 108}},
    {"cividis", 0.25, {67, 78, 107}},
    {"cividis", 0.3333333333333333, {87, 93, 109}},
    {"cividis", 0.4, {102, 105, 112}},
    {"cividis", 0.49999999999999994, {123, 123, 119}},
    {"cividis", 0.5, {124, 123, 120}},
    {"cividis", 0.6, {148, 142, 119}},
    {"cividis", 0.6666666666666666, {165, 155, 115}},
    {"cividis", 0.75, {187, 173, 108}},
    {"cividis", 0.8, {200, 183, 101}},
    {"cividis", 0.9, {228, 206, 81}},
    {"cividis", 0.9960937499999999, {253, 230, 54}},
    {"cividis", 0.99609375, {253, 231, 55}},
    {"cividis", 1.0, {253, 231, 55}},
    {"cividis", 1.5, {253, 231, 55}},
    {"coolwarm", -0.5, {58, 76, 192}},
    {"coolwarm", 0.0, {58, 76, 192}},
    {"coolwarm", 0.0039062499999999996, {58, 76, 192}},
    {"coolwarm", 0.00390625, {59, 77, 193}},
    {"coolwarm", 0.1, {88, 118, 226}},
    {"coolwarm", 0.2, {123, 158, 248}},
    {"coolwarm", 0.25, {141, 175, 253}},
    {"coolwarm", 0.3333333333333333, {170, 198, 253}},
    {"coolwarm", 0.4, {192, 211, 245}},
    {"coolwarm", 0.49999999999999994, {220, 220, 221}},
    {"coolwarm", 0.5, {221, 220, 219}},
    {"coolwarm", 0.6, {241, 202, 182}},
    {"coolwarm", 0.6666666666666666, {246, 183, 156}},
    {"coolwarm", 0.75, {243, 152, 121}},
    {"coolwarm", 0.8, {237, 132, 103}},
    {"coolwarm", 0.9, {214, 82, 67}},
    {"coolwarm", 0.9960937499999999, {181, 8, 39}},
    {"coolwarm", 0.99609375, {179, 3, 38}},
    {"coolwarm", 1.0, {179, 3, 38}},
    {"coolwarm", 1.5, {179, 3, 38}},
    {"gray", -0.5, {0, 0, 0}},
    {"gray", 0.0, {0, 0, 0}},
    {"gray", 0.0039062499999999996, {0, 0, 0}},
    {"gray", 0.00390625, {1, 1, 1}},
    {"gray", 0.1, {25, 25, 25}},
    {"gray", 0.2, {51, 51, 51}},
    {"gray", 0.25, {64, 64, 64}},
    {"gray", 0.3333333333333333, {85, 85, 85}},
    {"gray", 0.4, {102, 102, 102}},
    {"gray", 0.49999999999999994, {127, 127, 127}},
    {"gray", 0.5, {128, 128, 128}},
    {"gray", 0.6, {153, 153, 153}},
    {"gray", 0.6666666666666666, {170, 170, 170}},
    {"gray", 0.75, {192, 192, 192}},
    {"gray", 0.8, {204, 204, 204}},
    {"gray", 0.9, {230, 230, 230}},
    {"gray", 0.9960937499999999, {254, 254, 254}},
    {"gray", 0.99609375, {255, 255, 255}},
    {"gray", 1.0, {255, 255, 255}},
    {"gray", 1.5, {255, 255, 255}},
    {"viridis_r", -0.5, {253, 231, 36}},
    {"viridis_r", 0.0, {253, 231, 36}},
    {"viridis_r", 0.0039062499999999996, {253, 231, 36}},
    {"viridis_r", 0.00390625, {250, 230, 34}},
    {"viridis_r", 0.1, {189, 222, 38}},
    {"viridis_r", 0.2, {121, 209, 81}},
    {"viridis_r", 0.25, {91, 200, 98}},
    {"viridis_r", 0.3333333333333333, {53, 183, 120}},
    {"viridis_r", 0.4, {34, 167, 132}},
    {"viridis_r", 0.49999999999999994, {32, 144, 140}},
    {"viridis_r", 0.5, {32, 143, 140}},
    {"viridis_r", 0.6, {41, 120, 142}},
    {"viridis_r", 0.6666666666666666, {48, 103, 141}},
    {"viridis_r", 0.75, {59, 81, 138}},
    {"viridis_r", 0.8, {64, 67, 135}},
    {"viridis_r", 0.9, {72, 35, 116}},
    {"viridis_r", 0.9960937499999999, {68, 2, 85}},
    {"viridis_r", 0.99609375, {68, 1, 84}},
    {"viridis_r", 1.0, {68, 1, 84}},
    {"viridis_r", 1.5, {68, 1, 84}},
    {"magma_r", -0.5, {251, 252, 191}},
    {"magma_r", 0.0, {251, 252, 191}},
    {"magma_r", 0.0039062499999999996, {251, 252, 191}},
    {"magma_r", 0.00390625, {251, 250, 189}},
    {"magma_r", 0.1, {253, 207, 146}},
    {"magma_r", 0.2, {253, 159, 108}},
    {"magma_r", 0.25, {251, 134, 96}},
    {"magma_r", 0.3333333333333333, {240, 96, 93}},
    {"magma_r", 0.4, {221, 73, 104}},
    {"magma_r", 0.49999999999999994, {182, 54, 121}},
    {"magma_r", 0.5, {181, 54, 121}},
    {"magma_r", 0.6, {140, 41, 128}},
    {"magma_r", 0.6666666666666666, {113, 31, 129}},
    {"magma_r", 0.75, {79, 17, 123}},
    {"magma_r", 0.8, {59, 15, 111}},
    {"magma_r", 0.9, {20, 13, 53}},
    {"magma_r", 0.9960937499999999, {0, 0, 4}},
    {"magma_r", 0.99609375, {0, 0, 3}},
    {"magma_r", 1.0, {0, 0, 3}},
    {"magma_r", 1.5, {0, 0, 3}},
    {"inferno_r", -0.5, {252, 254, 164}},
    {"inferno_r", 0.0, {252, 254, 164}},
    {"inferno_r", 0.0039062499999999996, {252, 254, 164}},
    {"inferno_r", 0.00390625, {250, 253, 160}},
    {"inferno_r", 0.1, {245, 215, 69}},
    {"inferno_r", 0.2, {251, 164, 10}},
    {"inferno_r", 0.25, {249, 140, 9}},
    {"inferno_r", 0.3333333333333333, {237, 104, 37}},
    {"inferno_r", 0.4, {220, 80, 57}},
    {"inferno_r", 0.49999999999999994, {187, 55, 84}},
    {"inferno_r", 0.5, {186, 54, 85}},
    {"inferno_r", 0.6, {147, 37, 103}},
    {"inferno_r", 0.6666666666666666, {120, 28, 109}},
    {"inferno_r", 0.75, {85, 15, 109}},
    {"inferno_r", 0.8, {65, 9, 103}},
    {"inferno_r", 0.9, {22, 11, 57}},
    {"inferno_r", 0.9960937499999999, {0, 0, 4}},
    {"inferno_r", 0.99609375, {0, 0, 3}},
    {"inferno_r", 1.0, {0, 0, 3}},
    {"inferno_r", 1.5, {0, 0, 3}},
    {"plasma_r", -0.5, {239, 248, 33}},
    {"plasma_r", 0.0, {239, 248, 33}},
    {"plasma_r", 0.0039062499999999996, {239, 248, 33}},
    {"plasma_r", 0.00390625, {240, 246, 35}},
    {"plasma_r", 0.1, {252, 206, 37}},
    {"plasma_r", 0.2, {252, 166, 53}},
    {"plasma_r", 0.25, {247, 147, 65}},
    {"plasma_r", 0.3333333333333333, {236, 120, 83}},
    {"plasma_r", 0.4, {224, 100, 97}},
    {"plasma_r", 0.49999999999999994, {203, 71, 119}},
    {"plasma_r", 0.5, {202, 70, 120}},
    {"plasma_r", 0.6, {176, 42, 143}},
    {"plasma_r", 0.6666666666666666, {155, 23, 158}},
    {"plasma_r", 0.75, {124, 2, 167}},
    {"plasma_r", 0.8, {106, 0, 167}},
    {"plasma_r", 0.9, {64, 3, 156}},
    {"plasma_r", 0.9960937499999999, {16, 7, 135}},
    {"plasma_r", 0.99609375, {12, 7, 134}},
    {"plasma_r", 1.0, {12, 7, 134}},
    {"plasma_r", 1.5, {12, 7, 134}},
    {"cividis_r", -0.5, {253, 231, 55}},
    {"cividis_r", 0.0, {253, 231, 55}},
    {"cividis_r", 0.0039062499999999996, {253, 231, 55}},
    {"cividis_r", 0.00390625, {253, 230, 54}},
    {"cividis_r", 0.1, {228, 206, 81}},
    {"cividis_r", 0.2, {200, 183, 101}},
    {"cividis_r", 0.25, {186, 172, 108}},
    {"cividis_r", 0.3333333333333333, {165, 155, 115}},
    {"cividis_r", 0.4, {148, 142, 119}},
    {"cividis_r", 0.49999999999999994, {124, 123, 120}},
    {"cividis_r", 0.5, {123, 123, 119}},
    {"cividis_r", 0.6, {102, 105, 112}},
    {"cividis_r", 0.6666666666666666, {87, 93, 109}},
    {"cividis_r", 0.75, {66, 77, 107}},
    {"cividis_r", 0.8, {53, 69, 108}},
    {"cividis_r", 0.9, {8, 51, 112}},
    {"cividis_r", 0.9960937499999999, {0, 35, 79}},
    {"cividis_r", 0.99609375, {0, 34, 77}},
    {"cividis_r", 1.0, {0, 34, 77}},
    {"cividis_r", 1.5, {0, 34, 77}},
    {"coolwarm_r", -0.5, {179, 3, 38}},
    {"coolwarm_r", 0.0, {179, 3, 38}},
    {"coolwarm_r", 0.0039062499999999996, {179, 3, 38}},
    {"coolwarm_r", 0.00390625, {181, 8, 39}},
    {"coolwarm_r", 0.1, {214, 82, 67}},
    {"coolwarm_r", 0.2, {237, 132, 103}},
    {"coolwarm_r", 0.25, {244, 154, 123}},
    {"coolwarm_r", 0.3333333333333333, {246, 183, 156}},
    {"coolwarm_r", 0.4, {241, 202, 182}},
    {"coolwarm_r", 0.49999999999999994, {221, 220, 219}},
    {"coolwarm_r", 0.5, {220, 220, 221}},
    {"coolwarm_r", 0.6, {192, 211, 245}},
    {"coolwarm_r", 0.6666666666666666, {170, 198, 253}},
    {"coolwarm_r", 0.75, {139, 174, 253}},
    {"coolwarm_r", 0.8, {123, 158, 248}},
    {"coolwarm_r", 0.9, {88, 118, 226}},
    {"coolwarm_r", 0.9960937499999999, {59, 77, 193}},
    {"coolwarm_r", 0.99609375, {58, 76, 192}},
    {"coolwarm_r", 1.0, {58, 76, 192}},
    {"coolwarm_r", 1.5, {58, 76, 192}},
    {"gray_r", -0.5, {255, 255, 255}},
    {"gray_r", 0.0, {255, 255, 255}},
    {"gray_r", 0.0039062499999999996, {255, 255, 255}},
    {"gray_r", 0.00390625, {254, 254, 254}},
    {"gray_r", 0.1, {230, 230, 230}},
    {"gray_r", 0.2, {204, 204, 204}},
    {"gray_r", 0.25, {191, 191, 191}},
    {"gray_r", 0.3333333333333333, {170, 170, 170}},
    {"gray_r", 0.4, {153, 153, 153}},
    {"gray_r", 0.49999999999999994, {128, 128, 128}},
    {"gray_r", 0.5, {127, 127, 127}},
    {"gray_r", 0.6, {102, 102, 102}},
    {"gray_r", 0.6666666666666666, {85, 85, 85}},
    {"gray_r", 0.75, {63, 63, 63}},
    {"gray_r", 0.8, {50, 50, 50}},
    {"gray_r", 0.9, {24, 24, 24}},
    {"gray_r", 0.9960937499999999, {0, 0, 0}},
    {"gray_r", 0.99609375, {0, 0, 0}},
    {"gray_r", 1.0, {0, 0, 0}},
    {"gray_r", 1.5, {0, 0, 0}},
    // Where gray's 8 bits are not its entry number (33/255 in float64, times 255, is 32.99…), and
    // where matplotlib's gray_r is not gray read backwards (scripts/make-colormap-tables).
    {"gray", 0.130859375, {32, 32, 32}},       // entry 33
    {"gray", 0.146484375, {36, 36, 36}},       // entry 37
    {"gray", 0.259765625, {65, 65, 65}},       // entry 66
    {"gray", 0.517578125, {131, 131, 131}},    // entry 132
    {"gray_r", 0.044921875, {244, 244, 244}},  // entry 11
    {"gray_r", 0.548828125, {114, 114, 114}},  // entry 140
    {"gray_r", 0.759765625, {61, 61, 61}},     // entry 194
    {"gray_r", 0.994140625, {0, 0, 0}},        // entry 254
};

std::string rgbText(const Color& c) {
  return std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b);
}

}  // namespace

TEST_CASE("colormaps: colormapColor gives matplotlib's 8-bit colours at ~20 values of t on every map") {
  int checked = 0;
  for (const MatplotlibSample& sample : kMatplotlibSamples) {
    const std::optional<Colormap> map = colormapFromName(sample.name);
    REQUIRE_MESSAGE(map.has_value(), sample.name);
    const Color c = colormapColor(*map, sample.t);
    const Color expected{static_cast<std::uint8_t>(sample.rgb[0]), static_cast<std::uint8_t>(sample.rgb[1]),
                         static_cast<std::uint8_t>(sample.rgb[2]), 255};
    CHECK_MESSAGE(c == expected,
                  sample.name << " at t = " << sample.t << ": " << rgbText(c) << ", matplotlib " << rgbText(expected));
    ++checked;
  }
  CHECK(checked == 14 * 20 + 8);
}

TEST_CASE("colormaps: the names, seven maps and each reversed, read back") {
  const std::vector<std::string> names = colormapNames();
  REQUIRE(names.size() == 14);
  CHECK(names.front() == "viridis");
  CHECK(names[6] == "gray");
  CHECK(names[7] == "viridis_r");
  CHECK(names.back() == "gray_r");
  for (const std::string& name : names) {
    const std::optional<Colormap> map = colormapFromName(name);
    REQUIRE_MESSAGE(map.has_value(), name);
    CHECK(nameOf(*map) == name);
    CHECK(map->reversed == name.ends_with("_r"));
  }
  CHECK(colormapFromName("magma_r") == Colormap{ColormapName::magma, true});
  for (const char* bad : {"", "_r", "Viridis", "viridis_R", "viridis_r_r", "jet", "viridis ", "grey", "rainbow"}) {
    CHECK_MESSAGE(!colormapFromName(bad).has_value(), '"' << bad << '"');
  }
}

TEST_CASE("colormaps: a reversed map reads the table backwards") {
  for (const std::string name : {"viridis", "magma", "inferno", "plasma", "cividis", "coolwarm"}) {
    const Colormap forward = *colormapFromName(name);
    const Colormap backward = *colormapFromName(name + "_r");
    for (int i = 0; i < kColormapEntries; ++i) {
      const double t = (i + 0.5) / kColormapEntries;
      CHECK_MESSAGE(colormapColor(backward, t) == colormapColor(forward, 1.0 - t), name << " entry " << i);
    }
  }
}

TEST_CASE("colormaps: t is clamped to [0, 1], and NaN takes the first colour") {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const std::string& name : colormapNames()) {
    const Colormap map = *colormapFromName(name);
    const Color first = colormapColor(map, 0.0), last = colormapColor(map, 1.0);
    CHECK_MESSAGE(colormapColor(map, -1e-300) == first, name);
    CHECK_MESSAGE(colormapColor(map, -7.0) == first, name);
    CHECK_MESSAGE(colormapColor(map, -inf) == first, name);
    CHECK_MESSAGE(colormapColor(map, nan) == first, name);
    CHECK_MESSAGE(colormapColor(map, 1.0 + 1e-12) == last, name);
    CHECK_MESSAGE(colormapColor(map, 1e300) == last, name);
    CHECK_MESSAGE(colormapColor(map, inf) == last, name);
    CHECK_MESSAGE(first != last, name);
    CHECK(first.a == 255);
  }
}

TEST_CASE("colormaps: the tables' first, middle and last entries are matplotlib's float64 numbers") {
  struct Row {
    ColormapName name;
    ColormapEntry first, middle, last;  // entries 0, 128, 255
  };
  const std::vector<Row> rows = {
      {ColormapName::viridis,
       {0.267004, 0.004874, 0.329415},
       {0.127568, 0.566949, 0.550556},
       {0.993248, 0.906157, 0.143936}},
      {ColormapName::magma,
       {0.001462, 0.000466, 0.013866},
       {0.716387, 0.214982, 0.47529},
       {0.987053, 0.991438, 0.749504}},
      {ColormapName::inferno,
       {0.001462, 0.000466, 0.013866},
       {0.735683, 0.215906, 0.330245},
       {0.988362, 0.998364, 0.644924}},
      {ColormapName::plasma,
       {0.050383, 0.029803, 0.527975},
       {0.798216, 0.280197, 0.469538},
       {0.940015, 0.975158, 0.131326}},
      {ColormapName::cividis,
       {0.0, 0.135112, 0.304751},
       {0.488697, 0.485318, 0.471008},
       {0.995737, 0.909344, 0.217772}},
      {ColormapName::coolwarm,
       {0.2298057, 0.298717966, 0.753683153},
       {0.8674276350862745, 0.864376599772549, 0.8626024620196079},
       {0.705673158, 0.01555616, 0.150232812}},
      {ColormapName::gray,
       {0.0, 0.0, 0.0},
       {0.5019607843137255, 0.5019607843137255, 0.5019607843137255},
       {1.0, 1.0, 1.0}},
  };
  for (const Row& row : rows) {
    const auto& table = colormapTable(row.name);
    const std::string name = nameOf(Colormap{row.name, false});
    CHECK_MESSAGE(table[0] == row.first, name);  // exact: the same doubles
    CHECK_MESSAGE(table[128] == row.middle, name);
    CHECK_MESSAGE(table[255] == row.last, name);
  }
}

TEST_CASE("colours: CSS names, case-insensitive, and #rrggbb / #rrggbbaa in either case") {
  CHECK(colorFromText("orange") == Color{255, 165, 0, 255});
  CHECK(colorFromText("SteelBlue") == Color{70, 130, 180, 255});
  CHECK(colorFromText("REBECCAPURPLE") == Color{102, 51, 153, 255});
  CHECK(colorFromText("grey") == colorFromText("gray"));
  CHECK(colorFromText("#ff8000") == Color{255, 128, 0, 255});
  CHECK(colorFromText("#FF8000") == Color{255, 128, 0, 255});
  CHECK(colorFromText("#aBcDeF80") == Color{0xab, 0xcd, 0xef, 0x80});
  CHECK(colorFromText("#00000000") == Color{0, 0, 0, 0});
}

TEST_CASE("colours: anything else is refused") {
  for (const char* bad : {"",
                          "#",
                          "#12345",
                          "#1234567",
                          "#123456789",
                          "#ggg000",
                          "#12345g",
                          "#fff",
                          "#ffff",
                          "orange ",
                          " orange",
                          "oran ge",
                          "orange\n",
                          "0xff8000",
                          "ff8000",
                          "##ff8000",
                          "#ff 800",
                          "rgb(1,2,3)",
                          "none",
                          "transparent",
                          "tab:blue",
                          "C0",
                          "lightgoldenrodyellowx",
                          "\xc3\xa9"}) {
    CHECK_MESSAGE(!colorFromText(bad).has_value(), '"' << bad << '"');
  }
  CHECK_FALSE(colorFromText(std::string_view("red\0", 4)).has_value());
}

TEST_CASE("colours: 148 names, sorted, lower case, each reads back through hexText") {
  const std::vector<std::string>& names = colorNames();
  CHECK(names.size() == 148);
  CHECK(std::is_sorted(names.begin(), names.end()));
  CHECK(std::adjacent_find(names.begin(), names.end()) == names.end());
  for (const std::string& name : names) {
    const std::optional<Color> color = colorFromText(name);
    REQUIRE_MESSAGE(color.has_value(), name);
    CHECK(color->a == 255);
    const std::string hex = hexText(*color);
    CHECK_MESSAGE(hex.size() == 7, name << ": " << hex);
    CHECK_MESSAGE(colorFromText(hex) == color, name << ": " << hex);
  }
}

TEST_CASE("colours: hexText writes lower-case #rrggbb, and #rrggbbaa when not opaque") {
  CHECK(hexText(Color{255, 165, 0, 255}) == "#ffa500");
  CHECK(hexText(Color{0, 10, 171, 128}) == "#000aab80");
  CHECK(hexText(Color{1, 2, 3, 0}) == "#01020300");
  for (const Color c : {Color{0, 0, 0, 255}, Color{12, 200, 7, 254}, Color{255, 255, 255, 1}}) {
    CHECK(colorFromText(hexText(c)) == c);
  }
}
