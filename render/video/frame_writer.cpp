#include "render/video/frame_writer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "render/video/libav_util.hpp"

namespace particles::render {

bool isX264Preset(const std::string& name) {
  return std::find(kX264Presets.begin(), kX264Presets.end(), name) != kX264Presets.end();
}

int VideoOptions::keyframeInterval() const {
  return int(std::max(1.0, std::round(keyintSeconds * double(fps))));
}

std::unique_ptr<FrameWriter> openFrameWriter(const std::filesystem::path& path, const FrameWriterOptions& options) {
  const OutputFormat& format = outputFormatOf(path);
  checkAlpha(format, path, options.alpha);
  if (!format.open) {
    throw std::invalid_argument("'" + path.string() + "' is " + std::string(format.name) +
                                " output, one frame: render it (--at T) and call writePng");
  }
  return format.open(path, options);
}

long frameCount(double duration, int fps) {
  if (!(duration > 0.0) || fps < 1) throw std::invalid_argument("frameCount: duration and fps must be positive");
  return std::max(1L, std::lround(duration * fps));
}

void setLibavVerbose(bool verbose) {
  libav::setLogLevel(verbose ? AV_LOG_INFO : AV_LOG_ERROR);
}

}  // namespace particles::render
