#include "render/video/yuv420.hpp"

#include <bit>
#include <cstring>
#include <stdexcept>
#include <string>

namespace particles::render {

namespace {

// The formulas of yuv420.hpp in Q16: a level is 65536. Chroma coefficients are quartered because
// they multiply the sum of a 2 × 2 block.
constexpr int kOne = 1 << 16;
constexpr double kLumaScale = 219.0 / 255.0, kChromaScale = 224.0 / 255.0;
constexpr double kR = 0.2126, kG = 0.7152, kB = 0.0722;
constexpr int q16(double c) {
  return int(c * kOne + (c < 0 ? -0.5 : 0.5));
}
constexpr int kYr = q16(kLumaScale * kR), kYg = q16(kLumaScale * kG), kYb = q16(kLumaScale * kB);
constexpr int kUr = q16(kChromaScale * -kR / 1.8556 / 4), kUg = q16(kChromaScale * -kG / 1.8556 / 4);
constexpr int kUb = -kUr - kUg;  // grey (R = G = B) has Cb exactly 128
constexpr int kVg = q16(kChromaScale * -kG / 1.5748 / 4), kVb = q16(kChromaScale * -kB / 1.5748 / 4);
constexpr int kVr = -kVg - kVb;
constexpr int kLumaBias = 16 * kOne + kOne / 2, kChromaBias = 128 * kOne + kOne / 2;  // offset, rounding
static_assert(kYr + kYg + kYb == q16(kLumaScale), "white must give Y = 235");

// Pixel x of an RGBA row as one 32-bit load (memcpy: no alias or alignment assumption; it compiles
// to a plain load), which the vectoriser handles better than four byte loads. R is then the lowest
// byte on a little-endian machine, the highest on a big-endian one.
inline std::uint32_t loadPixel(const std::uint8_t* row, int x) {
  std::uint32_t p;
  std::memcpy(&p, row + 4 * std::ptrdiff_t(x), 4);
  return p;
}
inline std::uint32_t channel(std::uint32_t p, int index) {
  if constexpr (std::endian::native == std::endian::little) return (p >> (8 * index)) & 0xffu;
  return (p >> (24 - 8 * index)) & 0xffu;
}

// Plain loops over whole rows, so that the compiler vectorises them: this file is built with -O3,
// and target_clones adds an AVX2 version chosen at load time where the CPU has it (8 pixels a step
// instead of SSE2's 4, and SSE2 lacks 32-bit multiplies).
__attribute__((target_clones("avx2", "default"))) void lumaRow(const std::uint8_t* __restrict rgba,
                                                             std::uint8_t* __restrict y, int width) {
  for (int x = 0; x < width; ++x) {
    const std::uint32_t p = loadPixel(rgba, x);
    const int r = int(channel(p, 0)), g = int(channel(p, 1)), b = int(channel(p, 2));
    y[x] = std::uint8_t((kYr * r + kYg * g + kYb * b + kLumaBias) >> 16);
  }
}

__attribute__((target_clones("avx2", "default"))) void chromaRow(const std::uint8_t* __restrict top,
                                                               const std::uint8_t* __restrict bottom,
                                                               std::uint8_t* __restrict u,
                                                               std::uint8_t* __restrict v, int halfWidth) {
  for (int x = 0; x < halfWidth; ++x) {
    const std::uint32_t p0 = loadPixel(top, 2 * x), p1 = loadPixel(top, 2 * x + 1);
    const std::uint32_t p2 = loadPixel(bottom, 2 * x), p3 = loadPixel(bottom, 2 * x + 1);
    const int r = int(channel(p0, 0) + channel(p1, 0) + channel(p2, 0) + channel(p3, 0));
    const int g = int(channel(p0, 1) + channel(p1, 1) + channel(p2, 1) + channel(p3, 1));
    const int b = int(channel(p0, 2) + channel(p1, 2) + channel(p2, 2) + channel(p3, 2));
    u[x] = std::uint8_t((kUr * r + kUg * g + kUb * b + kChromaBias) >> 16);
    v[x] = std::uint8_t((kVr * r + kVg * g + kVb * b + kChromaBias) >> 16);
  }
}

// A block's chroma with each pixel's colour weighted by its alpha; the Q16 coefficients multiply a
// sum of four colours, so the weighted mean is scaled to four times itself. All four transparent:
// the plain sum (their colour, grey for the renderer's transparent black).
void chromaRowWeighted(const std::uint8_t* top, const std::uint8_t* bottom, std::uint8_t* u, std::uint8_t* v,
                       int halfWidth) {
  for (int x = 0; x < halfWidth; ++x) {
    const std::uint8_t* px[4] = {top + 8 * x, top + 8 * x + 4, bottom + 8 * x, bottom + 8 * x + 4};
    int weight = 0, sum[3] = {0, 0, 0}, plain[3] = {0, 0, 0};
    for (const std::uint8_t* p : px) {
      weight += p[3];
      for (int k = 0; k < 3; ++k) {
        sum[k] += p[k] * p[3];
        plain[k] += p[k];
      }
    }
    int block[3];
    for (int k = 0; k < 3; ++k) block[k] = weight ? (4 * sum[k] + weight / 2) / weight : plain[k];
    u[x] = std::uint8_t((kUr * block[0] + kUg * block[1] + kUb * block[2] + kChromaBias) >> 16);
    v[x] = std::uint8_t((kVr * block[0] + kVg * block[1] + kVb * block[2] + kChromaBias) >> 16);
  }
}

using ChromaRow = void (*)(const std::uint8_t* top, const std::uint8_t* bottom, std::uint8_t* u, std::uint8_t* v,
                           int halfWidth);

// Luma per pixel and chroma per 2 × 2 block (by `chromaRow`), row pair by row pair.
void convertRows(const Image& image, const Yuv420Planes& out, ChromaRow chroma) {
  const int w = image.width, h = image.height;
  if (w < 2 || h < 2 || (w & 1) || (h & 1)) {
    throw std::invalid_argument("yuv420p needs an even width and height, not " + std::to_string(w) + "x" +
                                std::to_string(h));
  }
  if (image.rgba.size() != image.stride() * std::size_t(h)) {
    throw std::invalid_argument("image of " + std::to_string(w) + "x" + std::to_string(h) + " holds " +
                                std::to_string(image.rgba.size()) + " bytes");
  }
  for (int row = 0; row < h; row += 2) {
    const std::uint8_t* top = image.pixel(0, row);
    const std::uint8_t* bottom = image.pixel(0, row + 1);
    lumaRow(top, out.y + std::ptrdiff_t(row) * out.yStride, w);
    lumaRow(bottom, out.y + std::ptrdiff_t(row + 1) * out.yStride, w);
    chroma(top, bottom, out.u + std::ptrdiff_t(row / 2) * out.uStride, out.v + std::ptrdiff_t(row / 2) * out.vStride,
           w / 2);
  }
}

}  // namespace

void rgbaToYuva420(const Image& image, const Yuv420Planes& out, std::uint8_t* alpha, int alphaStride) {
  convertRows(image, out, chromaRowWeighted);
  for (int row = 0; row < image.height; ++row) {
    const std::uint8_t* in = image.pixel(0, row);
    std::uint8_t* a = alpha + std::ptrdiff_t(row) * alphaStride;
    for (int x = 0; x < image.width; ++x) a[x] = in[4 * x + 3];
  }
}

void rgbaToYuv420(const Image& image, const Yuv420Planes& out) {
  convertRows(image, out, chromaRow);
}

}  // namespace particles::render
