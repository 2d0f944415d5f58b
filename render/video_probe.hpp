#pragma once
// Reads a video back through libavformat/libavcodec and decodes every frame: what the tests (and
// anyone checking an output) use to see that an MP4 is what was asked for.

#include <filesystem>
#include <string>

#include "render/image.hpp"

namespace particles::render {

struct VideoInfo {
  std::string codec;        // "h264"
  std::string pixelFormat;  // "yuv420p"
  int width = 0, height = 0;
  double fps = 0.0;              // the stream's average frame rate
  long frames = 0;               // frames actually decoded
  double durationSeconds = 0.0;  // the stream's duration (the container's if the stream has none)
  Image sample;                  // the decoded frame `sampleFrame` as RGBA (BT.709), if asked for
};

// Throws OutputError naming the failing libav call.
VideoInfo probeVideo(const std::filesystem::path& path, long sampleFrame = -1);

}  // namespace particles::render
