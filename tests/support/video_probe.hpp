#pragma once
// Reads a video back through libavformat/libavcodec and decodes every frame: what the tests use to
// see that an MP4, WebM or GIF is what was asked for. Test support (particles_test_support), not
// part of the renderer: the program never reads a video back.

#include <filesystem>
#include <string>

#include "render/image.hpp"

namespace particles::test {

struct VideoInfo {
  std::string codec;               // "h264"
  std::string pixelFormat;         // "yuv420p": the stream's, as the container states it
  std::string decodedPixelFormat;  // the decoder's frames': "yuva420p" from libvpx-vp9 for VP9 with alpha
  std::string alphaMode;           // the stream's "alpha_mode" tag: "1" for WebM with an alpha channel
  int width = 0, height = 0;
  double fps = 0.0;              // the stream's average frame rate
  long frames = 0;               // frames actually decoded
  double durationSeconds = 0.0;  // the stream's duration (the container's if the stream has none)
  render::Image sample;          // the decoded frame `sampleFrame` as RGBA (BT.709; alpha kept), if asked for
};

// Decodes with `decoder` ("libvpx-vp9", which unlike libavcodec's own vp9 decodes WebM's alpha),
// or, empty, libavcodec's choice for the stream's codec. Throws render::OutputError naming the
// failing libav call.
VideoInfo probeVideo(const std::filesystem::path& path, long sampleFrame = -1, const std::string& decoder = "");

}  // namespace particles::test
