#include "render/frame_writer.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include "render/gif_writer.hpp"
#include "render/libav_util.hpp"
#include "render/mp4_writer.hpp"
#include "render/png_sequence_writer.hpp"
#include "render/webm_writer.hpp"

namespace particles::render {

bool isX264Preset(const std::string& name) {
  static const char* const presets[] = {"ultrafast", "superfast", "veryfast", "faster",   "fast",
                                        "medium",    "slow",      "slower",   "veryslow", "placebo"};
  return std::any_of(std::begin(presets), std::end(presets), [&](const char* p) { return name == p; });
}

int VideoOptions::keyframeInterval() const {
  return int(std::max(1.0, std::round(keyintSeconds * double(fps))));
}

OutputKind outputKind(const std::filesystem::path& path) {
  const std::string s = path.string();
  std::error_code ec;
  if (!s.empty() && s.back() == '/') return OutputKind::pngSequence;
  if (std::filesystem::is_directory(path, ec)) return OutputKind::pngSequence;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext == ".mp4") return OutputKind::mp4;
  if (ext == ".webm") return OutputKind::webm;
  if (ext == ".gif") return OutputKind::gif;
  if (ext == ".png") return OutputKind::png;
  throw std::invalid_argument("cannot tell what to write to '" + s +
                              "': use file.mp4 (H.264 video), file.webm (VP9 video), file.gif (animated GIF), "
                              "file.png with --at T (one frame) or dir/ (PNG sequence)");
}

bool keepsAlpha(OutputKind kind) {
  return kind == OutputKind::webm || kind == OutputKind::png || kind == OutputKind::pngSequence;
}

std::string outputKindName(OutputKind kind) {
  switch (kind) {
    case OutputKind::mp4: return "MP4";
    case OutputKind::webm: return "WebM";
    case OutputKind::gif: return "GIF";
    case OutputKind::png: return "PNG";
    case OutputKind::pngSequence: return "PNG sequence";
  }
  return "?";
}

std::unique_ptr<FrameWriter> openFrameWriter(const std::filesystem::path& path, const FrameWriterOptions& options) {
  const OutputKind kind = outputKind(path);
  if (options.alpha && !keepsAlpha(kind)) {
    throw std::invalid_argument(outputKindName(kind) + " output '" + path.string() +
                                "' cannot keep a transparent background: write .webm, .png or dir/");
  }
  switch (kind) {
    case OutputKind::mp4: return std::make_unique<Mp4Writer>(path, options);
    case OutputKind::webm: return std::make_unique<WebmWriter>(path, options);
    case OutputKind::gif: return std::make_unique<GifWriter>(path, options);
    case OutputKind::pngSequence: return std::make_unique<PngSequenceWriter>(path, options);
    case OutputKind::png: break;
  }
  throw std::invalid_argument("'" + path.string() + "' is a single PNG: render one frame (--at T) and call writePng");
}

long frameCount(double duration, int fps) {
  if (!(duration > 0.0) || fps < 1) throw std::invalid_argument("frameCount: duration and fps must be positive");
  return std::max(1L, std::lround(duration * fps));
}

void setLibavVerbose(bool verbose) {
  av_log_set_level(verbose ? AV_LOG_INFO : AV_LOG_ERROR);
}

}  // namespace particles::render
