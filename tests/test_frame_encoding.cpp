// What happens to a frame between the renderer and the encoder: RGBA → yuv420p (render/video/yuv420.hpp)
// against the BT.709 formulas in double precision, and the writer's pipeline (render/video/frame_pipeline.hpp):
// order, slot reuse, and errors from either side.

#include <doctest/doctest.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <thread>
#include <vector>

#include "render/video/frame_pipeline.hpp"
#include "render/image.hpp"
#include "render/video/yuv420.hpp"

using namespace particles::render;

namespace {

// BT.709, full-range RGB in, limited-range YUV out: the formulas of render/video/yuv420.hpp.
struct Yuv {
  double y, u, v;
};
Yuv bt709(double r, double g, double b) {
  const double luma = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  return {16 + 219.0 / 255.0 * luma, 128 + 224.0 / 255.0 * (b - luma) / 1.8556,
          128 + 224.0 / 255.0 * (r - luma) / 1.5748};
}

// Planes with strides wider than the picture; the padding must stay untouched.
struct Planes {
  static constexpr std::uint8_t kPadding = 0xA5;
  int width, height, yStride, cStride, vStride;  // U and V strides differ, so neither is taken for the other
  std::vector<std::uint8_t> y, u, v;
  Planes(int w, int h)
      : width(w),
        height(h),
        yStride(w + 7),
        cStride(w / 2 + 5),
        vStride(w / 2 + 9),
        y(std::size_t(yStride) * h, kPadding),
        u(std::size_t(cStride) * (h / 2), kPadding),
        v(std::size_t(vStride) * (h / 2), kPadding) {}
  Yuv420Planes view() { return {y.data(), u.data(), v.data(), yStride, cStride, vStride}; }
  int Y(int x, int row) const { return y[std::size_t(row) * yStride + x]; }
  int U(int x, int row) const { return u[std::size_t(row) * cStride + x]; }
  int V(int x, int row) const { return v[std::size_t(row) * vStride + x]; }
  bool paddingIntact() const {
    for (int row = 0; row < height; ++row) {
      for (int x = width; x < yStride; ++x) if (Y(x, row) != kPadding) return false;
    }
    for (int row = 0; row < height / 2; ++row) {
      for (int x = width / 2; x < cStride; ++x) if (U(x, row) != kPadding) return false;
      for (int x = width / 2; x < vStride; ++x) if (V(x, row) != kPadding) return false;
    }
    return true;
  }
};

Image filled(int w, int h, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  Image image(w, h);
  for (int row = 0; row < h; ++row) {
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = image.pixel(x, row);
      p[0] = r, p[1] = g, p[2] = b, p[3] = 255;
    }
  }
  return image;
}

// splitmix64: the same "random" picture on every machine.
std::uint64_t nextRandom(std::uint64_t& state) {
  std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace

TEST_CASE("RGBA to yuv420p follows BT.709 limited range, rounded to nearest") {
  // Odd widths of the half-row (a vector loop's remainder) and more than one vector's worth.
  for (const auto& [w, h] : {std::pair{70, 6}, std::pair{2, 2}, std::pair{1280, 4}}) {
    CAPTURE(w);
    Image image(w, h);
    std::uint64_t state = 2026;
    for (std::uint8_t& byte : image.rgba) byte = std::uint8_t(nextRandom(state));
    Planes out(w, h);
    rgbaToYuv420(image, out.view());
    double worst = 0;
    for (int row = 0; row < h; ++row) {
      for (int x = 0; x < w; ++x) {
        const std::uint8_t* p = image.pixel(x, row);
        worst = std::max(worst, std::abs(out.Y(x, row) - bt709(p[0], p[1], p[2]).y));
      }
    }
    for (int row = 0; row < h / 2; ++row) {
      for (int x = 0; x < w / 2; ++x) {
        double mean[3] = {};
        for (int k = 0; k < 3; ++k) {
          mean[k] = (image.pixel(2 * x, 2 * row)[k] + image.pixel(2 * x + 1, 2 * row)[k] +
                     image.pixel(2 * x, 2 * row + 1)[k] + image.pixel(2 * x + 1, 2 * row + 1)[k]) / 4.0;
        }
        const Yuv exact = bt709(mean[0], mean[1], mean[2]);
        worst = std::max({worst, std::abs(out.U(x, row) - exact.u), std::abs(out.V(x, row) - exact.v)});
      }
    }
    // Rounded to nearest, with Q16 coefficients: within half a level and 1/64.
    CHECK(worst <= 0.5 + 1.0 / 64);
    CHECK(out.paddingIntact());
  }
}

TEST_CASE("black, white, grey and the primaries land on their BT.709 codes") {
  struct Case {
    std::array<std::uint8_t, 3> rgb;
    std::array<int, 3> yuv;
  };
  // ITU-R BT.709-6 limited range: Y 16…235, chroma 16…240; grey has no chroma.
  const Case cases[] = {{{0, 0, 0}, {16, 128, 128}},      {{255, 255, 255}, {235, 128, 128}},
                        {{128, 128, 128}, {126, 128, 128}}, {{255, 0, 0}, {63, 102, 240}},
                        {{0, 255, 0}, {173, 42, 26}},       {{0, 0, 255}, {32, 240, 118}}};
  for (const Case& c : cases) {
    CAPTURE(int(c.rgb[0]));
    CAPTURE(int(c.rgb[1]));
    CAPTURE(int(c.rgb[2]));
    Planes out(4, 2);
    rgbaToYuv420(filled(4, 2, c.rgb[0], c.rgb[1], c.rgb[2]), out.view());
    CHECK(out.Y(3, 1) == c.yuv[0]);
    CHECK(out.U(1, 0) == c.yuv[1]);
    CHECK(out.V(1, 0) == c.yuv[2]);
  }
}

TEST_CASE("yuv420p needs an even size") {
  Planes out(4, 4);
  CHECK_THROWS_AS(rgbaToYuv420(Image(3, 4), out.view()), std::invalid_argument);
  CHECK_THROWS_AS(rgbaToYuv420(Image(4, 1), out.view()), std::invalid_argument);
  Image truncated(4, 4);
  truncated.rgba.resize(8);
  CHECK_THROWS_AS(rgbaToYuv420(truncated, out.view()), std::invalid_argument);
}

TEST_CASE("the frame pipeline consumes every frame in order through a few reused slots") {
  constexpr std::size_t capacity = 2;
  const std::size_t slots = FramePipeline::slotCount(capacity);
  CHECK(slots == capacity + 2);
  // Each slot's state: 0 free, 1 being filled, 2 queued, 3 being consumed. Any other transition
  // means two threads shared a slot.
  std::vector<std::atomic<int>> state(slots);
  std::vector<int> content(slots, -1);
  std::vector<long> consumed;
  std::atomic<int> misuse{0};
  auto move = [&](std::size_t slot, int from, int to) {
    if (slot >= slots || !state[slot].compare_exchange_strong(from, to)) ++misuse;
  };
  {
    FramePipeline pipeline(
        capacity,
        [&](const Image& frame, std::size_t slot) {
          move(slot, 0, 1);
          content[slot] = frame.width;
          move(slot, 1, 2);
        },
        [&](std::size_t slot, long index) {
          move(slot, 2, 3);
          if (content[slot] != index + 2) ++misuse;  // frame i is 2 + i wide
          consumed.push_back(index);
          move(slot, 3, 0);
        });
    for (int i = 0; i < 200; ++i) pipeline.push(Image(2 + i, 1));
    pipeline.close();
  }
  CHECK(misuse == 0);
  REQUIRE(consumed.size() == 200);
  for (long i = 0; i < 200; ++i) CHECK(consumed[std::size_t(i)] == i);
}

TEST_CASE("a failing fill leaves the pipeline usable, a failing consumer stops it") {
  std::vector<long> consumed;
  {
    FramePipeline pipeline(
        1,
        [](const Image& frame, std::size_t) {
          if (frame.width == 0) throw std::runtime_error("cannot convert");
        },
        [&](std::size_t, long index) { consumed.push_back(index); });
    // Many failures in a row: each returns its slot, or the pipeline would run out of them.
    for (int i = 0; i < 10; ++i) CHECK_THROWS_WITH(pipeline.push(Image()), "cannot convert");
    pipeline.push(Image(2, 2));
    pipeline.close();
  }
  CHECK(consumed == std::vector<long>{0});

  FramePipeline failing(
      1, [](const Image&, std::size_t) {}, [](std::size_t, long) { throw std::runtime_error("disk full"); });
  failing.push(Image(2, 2));
  // The worker fails on the first frame; a later push or the close reports it.
  CHECK_THROWS_WITH(
      {
        for (int i = 0; i < 1000; ++i) failing.push(Image(2, 2));
        failing.close();
      },
      "disk full");
}

TEST_CASE("a pipeline of capacity 0 fills and consumes each frame on the calling thread, in order") {
  CHECK(FramePipeline::slotCount(0) == 1);
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<long> consumed;
  int width = -1;
  bool elsewhere = false;
  {
    FramePipeline pipeline(
        0,
        [&](const Image& frame, std::size_t slot) {
          elsewhere = elsewhere || slot != 0 || std::this_thread::get_id() != caller;
          width = frame.width;
        },
        [&](std::size_t slot, long index) {
          elsewhere = elsewhere || slot != 0 || std::this_thread::get_id() != caller;
          if (width != index + 2) elsewhere = true;  // frame i is 2 + i wide, consumed before the next fill
          consumed.push_back(index);
        });
    for (int i = 0; i < 5; ++i) {
      pipeline.push(Image(2 + i, 1));
      CHECK(consumed.size() == size_t(i + 1));  // consumed before push returned
    }
    pipeline.close();
  }
  CHECK_FALSE(elsewhere);
  CHECK(consumed == std::vector<long>{0, 1, 2, 3, 4});

  // A failing consumer: that push reports it, and so does every later one.
  FramePipeline failing(
      0, [](const Image&, std::size_t) {}, [](std::size_t, long) { throw std::runtime_error("disk full"); });
  CHECK_THROWS_WITH(failing.push(Image(2, 2)), "disk full");
  CHECK_THROWS_WITH(failing.push(Image(2, 2)), "disk full");
}
