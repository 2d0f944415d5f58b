#pragma once
// An RGBA8 image, top row first, 4 bytes per pixel (R, G, B, A): what the renderer produces and
// the writers consume. Frames from the renderer are opaque (A = 255 everywhere).

#include <cstddef>
#include <cstdint>
#include <vector>

namespace particles::render {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;  // width · height · 4 bytes

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgba(std::size_t(w) * std::size_t(h) * 4, 0) {}
  std::size_t stride() const { return std::size_t(width) * 4; }
  const std::uint8_t* pixel(int x, int y) const { return rgba.data() + std::size_t(y) * stride() + std::size_t(x) * 4; }
  std::uint8_t* pixel(int x, int y) { return rgba.data() + std::size_t(y) * stride() + std::size_t(x) * 4; }
  bool operator==(const Image&) const = default;
};

}  // namespace particles::render
