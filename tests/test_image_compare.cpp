// The golden-frame comparison (render/image_compare.hpp, docs/physics.md §10) on small hand-made images:
// the per-channel threshold, the share and its bound, the largest difference, the bounding box,
// size mismatches and the diff picture.
#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "render/image_compare.hpp"

using particles::render::compareImages;
using particles::render::CompareTolerance;
using particles::render::diffImage;
using particles::render::Image;
using particles::render::ImageComparison;
using particles::render::PixelBox;

namespace {

// An opaque image solidImage with one colour.
Image solidImage(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image img(w, h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  }
  return img;
}

bool hasRgb(const Image& img, int x, int y, const std::uint8_t (&rgb)[3]) {
  const std::uint8_t* p = img.pixel(x, y);
  return p[0] == rgb[0] && p[1] == rgb[1] && p[2] == rgb[2] && p[3] == 255;
}

}  // namespace

TEST_CASE("image compare: identical images match, with nothing to report") {
  const Image a = solidImage(8, 6, 10, 20, 30);
  const ImageComparison c = compareImages(a, a);
  CHECK(c.width == 8);
  CHECK(c.height == 6);
  CHECK(c.pixels == 48);
  CHECK(c.differing == 0);
  CHECK(c.share == 0.0);
  CHECK(c.largestDifference == 0);
  CHECK_FALSE(c.box.has_value());
  CHECK(c.passed);
}

TEST_CASE("image compare: a pixel differs when any channel differs by more than the threshold") {
  const Image a = solidImage(4, 4, 100, 100, 100);
  for (int channel = 0; channel < 4; ++channel) {
    CAPTURE(channel);
    Image b = a;
    b.pixel(1, 2)[channel] = std::uint8_t(b.pixel(1, 2)[channel] - 16);  // exactly the threshold: equal
    ImageComparison c = compareImages(a, b, {16, 0.0});
    CHECK(c.differing == 0);
    CHECK(c.largestDifference == 16);  // reported whatever the threshold
    CHECK(c.passed);

    b.pixel(1, 2)[channel] = std::uint8_t(a.pixel(1, 2)[channel] - 17);  // one above: different
    c = compareImages(a, b, {16, 0.0});
    CHECK(c.differing == 1);
    CHECK(c.largestDifference == 17);
    CHECK_FALSE(c.passed);
    REQUIRE(c.box.has_value());
    CHECK(*c.box == PixelBox{1, 2, 1, 2});
  }
  // The sign does not matter, and the largest difference is the largest over every channel.
  Image b = a;
  b.pixel(3, 0)[0] = 255;  // +155
  b.pixel(0, 3)[2] = 0;    // -100
  const ImageComparison c = compareImages(a, b, {0, 1.0});
  CHECK(c.differing == 2);
  CHECK(c.largestDifference == 155);
}

TEST_CASE("image compare: share of differing pixels against the bound, boundary included") {
  const Image a = solidImage(10, 10, 0, 0, 0);  // 100 pixels
  Image b = a;
  for (int x = 0; x < 5; ++x) b.pixel(x, 4)[1] = 200;  // 5 pixels
  ImageComparison c = compareImages(a, b, {16, 0.05});
  CHECK(c.differing == 5);
  CHECK(c.share == doctest::Approx(0.05));
  CHECK(c.passed);  // share ≤ bound passes
  c = compareImages(a, b, {16, 0.04});
  CHECK_FALSE(c.passed);
  c = compareImages(a, b, {200, 0.0});  // below the threshold: no pixel counts
  CHECK(c.differing == 0);
  CHECK(c.passed);
}

TEST_CASE("image compare: the bounding box encloses exactly the differing pixels") {
  const Image a = solidImage(20, 10, 50, 50, 50);
  Image b = a;
  b.pixel(2, 3)[0] = 0;
  b.pixel(7, 1)[1] = 0;
  b.pixel(15, 8)[2] = 0;
  b.pixel(18, 0)[0] = 60;  // within the threshold: not in the box
  const ImageComparison c = compareImages(a, b);
  REQUIRE(c.box.has_value());
  CHECK(*c.box == PixelBox{2, 1, 15, 8});
  CHECK(c.box->width() == 14);
  CHECK(c.box->height() == 8);
  CHECK(c.differing == 3);
}

TEST_CASE("image compare: sizes that do not match are refused with both sizes named") {
  const Image a = solidImage(320, 240, 0, 0, 0);
  const Image b = solidImage(640, 480, 0, 0, 0);
  CHECK(particles::render::sizeMismatch(a, a).empty());
  const std::string message = particles::render::sizeMismatch(a, b);
  CHECK(message.find("320×240") != std::string::npos);
  CHECK(message.find("640×480") != std::string::npos);
  CHECK(message.find("320×240") < message.find("640×480"));  // expected first
  CHECK_THROWS_AS(compareImages(a, b), std::invalid_argument);
  CHECK_THROWS_AS(diffImage(a, b), std::invalid_argument);
  CHECK_THROWS_AS(compareImages(solidImage(4, 3, 0, 0, 0), solidImage(3, 4, 0, 0, 0)), std::invalid_argument);
}

TEST_CASE("image compare: tolerances out of range are refused") {
  const Image a = solidImage(2, 2, 0, 0, 0);
  CHECK_THROWS_AS(compareImages(a, a, {-1, 0.1}), std::invalid_argument);
  CHECK_THROWS_AS(compareImages(a, a, {256, 0.1}), std::invalid_argument);
  CHECK_THROWS_AS(compareImages(a, a, {0, -0.1}), std::invalid_argument);
  CHECK_THROWS_AS(compareImages(a, a, {0, 1.5}), std::invalid_argument);
  CHECK_THROWS_AS(compareImages(a, a, {0, std::nan("")}), std::invalid_argument);
  CHECK_NOTHROW(compareImages(a, a, {255, 1.0}));
}

TEST_CASE("image compare: empty images match") {
  const ImageComparison c = compareImages(Image(), Image());
  CHECK(c.pixels == 0);
  CHECK(c.share == 0.0);
  CHECK(c.passed);
}

TEST_CASE("image compare: the defaults are those documented in golden/README.md") {
  const CompareTolerance t;
  CHECK(t.threshold == 16);
  CHECK(t.maxShare == 0.0002);
}

TEST_CASE("image compare: the diff picture highlights differences over a dimmed grey expected frame") {
  using namespace particles::render;
  const Image expected = solidImage(12, 10, 200, 100, 50);
  Image actual = expected;
  actual.pixel(5, 4)[0] = 0;    // far above the threshold
  actual.pixel(7, 6)[3] = 100;  // alpha counts too
  actual.pixel(1, 1)[1] = 105;  // a near miss: differs, within the threshold
  const Image diff = diffImage(expected, actual, 16);
  REQUIRE(diff.width == 12);
  REQUIRE(diff.height == 10);

  CHECK(hasRgb(diff, 5, 4, kDiffHighlight));
  CHECK(hasRgb(diff, 7, 6, kDiffHighlight));
  CHECK(hasRgb(diff, 1, 1, kDiffNearMiss));
  // The box of the differing pixels is x 5…7, y 4…6; its outline runs one pixel outside it.
  for (int x = 4; x <= 8; ++x) {
    CAPTURE(x);
    CHECK(hasRgb(diff, x, 3, kDiffBox));
    CHECK(hasRgb(diff, x, 7, kDiffBox));
  }
  for (int y = 3; y <= 7; ++y) {
    CAPTURE(y);
    CHECK(hasRgb(diff, 4, y, kDiffBox));
    CHECK(hasRgb(diff, 8, y, kDiffBox));
  }
  // Everything else: the expected pixel's luma, dimmed, in grey, opaque.
  const double luma = 0.299 * 200 + 0.587 * 100 + 0.114 * 50;
  const auto grey = std::uint8_t(std::lround(kDiffDim * luma));
  for (const auto& [x, y] : {std::pair{0, 0}, std::pair{6, 5}, std::pair{11, 9}, std::pair{3, 8}}) {
    CAPTURE(x);
    CAPTURE(y);
    const std::uint8_t* p = diff.pixel(x, y);
    CHECK(p[0] == grey);
    CHECK(p[1] == grey);
    CHECK(p[2] == grey);
    CHECK(p[3] == 255);
  }
}

TEST_CASE("image compare: the box outline is clipped at the image border and spares highlighted pixels") {
  using namespace particles::render;
  const Image expected = solidImage(6, 5, 0, 0, 0);
  Image actual = expected;
  actual.pixel(0, 0)[0] = 255;
  actual.pixel(2, 0)[0] = 255;
  const Image diff = diffImage(expected, actual);
  // The box is x 0…2, y 0…0: the outline would be at x −1 and y −1 (clipped to 0, where the
  // highlighted pixels stay), at x 3 and at y 1.
  CHECK(hasRgb(diff, 0, 0, kDiffHighlight));
  CHECK(hasRgb(diff, 2, 0, kDiffHighlight));
  CHECK(hasRgb(diff, 1, 0, kDiffBox));
  CHECK(hasRgb(diff, 3, 0, kDiffBox));
  CHECK(hasRgb(diff, 3, 1, kDiffBox));
  CHECK(hasRgb(diff, 0, 1, kDiffBox));
  CHECK_FALSE(hasRgb(diff, 4, 0, kDiffBox));
  CHECK_FALSE(hasRgb(diff, 0, 2, kDiffBox));
  // Identical images: no highlight and no box at all.
  const Image same = diffImage(expected, expected);
  for (int y = 0; y < same.height; ++y) {
    for (int x = 0; x < same.width; ++x) CHECK(same.pixel(x, y)[0] == 0);
  }
}
