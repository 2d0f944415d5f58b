#pragma once
// Animated GIF output with one palette made for the whole video, through libavfilter's palettegen
// and paletteuse, libavcodec's gif encoder and libavformat's gif muxer. A palette for the whole
// video needs every frame before the first can be mapped to it, so there are two passes:
//   1. as frames arrive (on the pipeline's worker): each frame is counted into palettegen's
//      histogram and kept, deflated (zlib level 1), in memory;
//   2. in finish(): palettegen gives the palette; each kept frame is inflated again, mapped to the
//      palette by paletteuse, encoded and muxed.
// Kept frames cost little: a cloth frame deflates to a fiftieth of its size, in a fraction of the
// time the frame took to draw (bench/README.md, "GIF frames deflated").
//
// Palette: palettegen's stats_mode=full counts every pixel of every frame, so the flat colours
// that cover most of a frame (background, particles, bodies) get exact entries and the rest
// (anti-aliased edges, strain colours) share what is left; no entry is reserved for transparency.
// Dithering: none, which came out closest to the frames and smallest (bench/README.md, "GIF
// dithering"); the soft body in the light theme has under 256 colours and is exact. Flat
// colours stay flat, with no dither pattern crawling from frame to frame. paletteuse's
// diff_mode=rectangle maps only the part of a frame that changed.
//
// Timing: GIF delays are whole centiseconds. Frame i is shown from round(100·i / fps) cs, so at
// 30 fps the delays run 3, 4, 3, 3, 4, 3, … cs and each frame starts within 5 ms of i / fps; the
// last frame's delay (the muxer's final_delay) ends the animation at round(100·n / fps) cs, the
// video's length. fps is 1 … the cap of GIF's row (output_formats.cpp). The GIF loops forever.
//
// Any size (palettised, no chroma subsampling); no alpha: GIF has one transparent colour, which
// cannot hold anti-aliased edges over nothing (FrameWriterOptions::alpha is refused).

#include <memory>

#include "render/video/frame_writer.hpp"
#include "render/video/single_file_writer.hpp"

namespace particles::render {

class GifWriter final : public SingleFileWriter {
 public:
  // Opens the temporary file and the palette's filter graph. Throws std::invalid_argument for bad
  // options (fps above GIF's cap, output_formats.cpp), OutputError naming the failing libav call and its message.
  GifWriter(const std::filesystem::path& path, const FrameWriterOptions& options);
  ~GifWriter() override;  // abort() unless finished

 private:
  void complete() override;
  void release() noexcept override;

  struct Passes;
  std::unique_ptr<Passes> passes_;
};

}  // namespace particles::render
