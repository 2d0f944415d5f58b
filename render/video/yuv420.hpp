#pragma once
// Internal to render/: the renderer's RGBA frames as H.264 wants them, yuv420p with BT.709
// coefficients in limited range (ITU-R BT.709-6 §3; Y in 16…235, Cb and Cr in 16…240), the colour
// tags the MP4 carries (render/video/mp4_writer.hpp). For full-range R, G, B in 0…255:
//   Y  = 16  + 219/255 · (0.2126 R + 0.7152 G + 0.0722 B)
//   Cb = 128 + 224/255 · (B − Y′) / 1.8556,   Cr = 128 + 224/255 · (R − Y′) / 1.5748
// with Y′ = 0.2126 R + 0.7152 G + 0.0722 B; each 2 × 2 block of pixels shares one Cb and Cr, taken
// from the block's mean colour (chroma centred in the block), so a thin coloured line keeps its hue.
// rgbaToYuv420 ignores alpha (opaque frames). rgbaToYuva420 keeps it as a fourth, full-resolution
// plane (0 … 255, VP9's alpha in WebM) and takes a block's chroma from its colours weighted by their
// alpha: a transparent pixel's colour is nothing, and averaged in evenly it would tint the edges of
// shapes (with the renderer's straight colour, black for the transparent background).
//
// Written here rather than through libswscale: with the flags that keep chroma exact
// (ACCURATE_RND | FULL_CHR_H_INP) swscale takes its unvectorised path, about four times slower than
// this loop with AVX2 (bench/README.md, "Our own yuv420p").
// Results equal the formulas above rounded to nearest within 1/64 of a level (Q16 fixed point).

#include <cstdint>

#include "render/image.hpp"

namespace particles::render {

// Destination planes: Y is width × height, U and V are width/2 × height/2; strides in bytes.
struct Yuv420Planes {
  std::uint8_t* y;
  std::uint8_t* u;
  std::uint8_t* v;
  int yStride, uStride, vStride;
};

// Converts `image` (even width and height, else std::invalid_argument) into `out`.
void rgbaToYuv420(const Image& image, const Yuv420Planes& out);
// The same with alpha into `alpha` (width × height, `alphaStride` bytes a row), chroma weighted by
// alpha. A scalar loop: it feeds VP9, whose encoding costs far more.
void rgbaToYuva420(const Image& image, const Yuv420Planes& out, std::uint8_t* alpha, int alphaStride);

}  // namespace particles::render
