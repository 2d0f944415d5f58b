#include "render/video/mp4_writer.hpp"

#include <fmt/format.h>

#include <string>

#include "render/video/output_formats.hpp"
#include "render/video/video_encoder.hpp"

namespace particles::render {

namespace {

void validateMp4Options(const FrameWriterOptions& o) {
  validateYuvVideo(outputFormat(OutputKind::mp4), o);
  crfOf(outputFormat(OutputKind::mp4), o.video.crf);
  if (!isX264Preset(o.video.preset)) {
    throw std::invalid_argument(
        fmt::format("unknown x264 preset '{}' ({})", o.video.preset, fmt::join(kX264Presets, ", ")));
  }
  static const char* const tunes[] = {"",     "film", "animation",  "grain",      "stillimage",
                                      "psnr", "ssim", "fastdecode", "zerolatency"};
  bool tuneOk = false;
  for (const char* t : tunes) tuneOk = tuneOk || o.video.tune == t;
  if (!tuneOk) throw std::invalid_argument("unknown x264 tune '" + o.video.tune + "'");
}

// The options are checked before the output is opened: opening a FIFO waits for its reader, and
// bad options would then be reported only once one came.
const std::filesystem::path& validatedMp4Path(const std::filesystem::path& path, const FrameWriterOptions& options) {
  validateMp4Options(options);
  return path;
}

}  // namespace

Mp4Writer::Mp4Writer(const std::filesystem::path& path, const FrameWriterOptions& options)
    : YuvVideoWriter(validatedMp4Path(path, options), options) {
  std::unique_ptr<VideoEncoder> video = makeEncoder("mp4", "libx264", false);
  // x264's keyint: the longest run between keyframes. Its min-keyint (libav's keyint_min, default
  // 25) is clamped by x264 to half of it plus one.
  video->codec()->gop_size = options.video.keyframeInterval();
  if (options.video.encoderThreads > 0) video->codec()->thread_count = options.video.encoderThreads;
  video->setOption("preset", options.video.preset);
  if (!options.video.tune.empty()) video->setOption("tune", options.video.tune);
  video->setOption("crf", std::to_string(crfOf(outputFormat(OutputKind::mp4), options.video.crf)));
  start(std::move(video), {{"movflags", "+faststart"}});
}

}  // namespace particles::render
