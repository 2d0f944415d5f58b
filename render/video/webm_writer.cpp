#include "render/video/webm_writer.hpp"

#include <string>

#include "render/video/output_formats.hpp"
#include "render/video/video_encoder.hpp"

namespace particles::render {

namespace {

// libvpx's speed for deadline "good", 0 (slowest) … 5 (libvpx 1.12 treats more as 5). 4 encoded
// fastest of those measured (bench/README.md, "VP9 speed").
constexpr int kVp9Threads = 4;
constexpr int kVp9CpuUsed = 4;

void validateWebmOptions(const FrameWriterOptions& o) {
  validateYuvVideo(outputFormat(OutputKind::webm), o);
  crfOf(outputFormat(OutputKind::webm), o.video.crf);
}

const std::filesystem::path& validatedWebmPath(const std::filesystem::path& path, const FrameWriterOptions& options) {
  validateWebmOptions(options);  // before the output is opened, as Mp4Writer does
  return path;
}

}  // namespace

WebmWriter::WebmWriter(const std::filesystem::path& path, const FrameWriterOptions& options)
    : YuvVideoWriter(validatedWebmPath(path, options), options) {
  std::unique_ptr<VideoEncoder> video = makeEncoder("webm", "libvpx-vp9", options.alpha);
  AVCodecContext* c = video->codec();
  c->gop_size = options.video.keyframeInterval();  // libvpx's kf_max_dist
  c->bit_rate = 0;                                 // with crf: constant quality, no bit-rate target
  // A fixed number of threads, not one per core: libvpx's output depends on its thread count (its
  // tiles and row synchronisation), and the same command must give the same bytes on any machine
  // (measured: 1 core against 2 gave different files with one thread per core).
  c->thread_count = kVp9Threads;
  video->setOption("crf", std::to_string(crfOf(outputFormat(OutputKind::webm), options.video.crf)));
  video->setOption("deadline", "good");
  video->setOption("cpu-used", std::to_string(kVp9CpuUsed));
  video->setOption("row-mt", "1");
  // Matroska's track ids are random otherwise.
  video->format()->flags |= AVFMT_FLAG_BITEXACT;
  start(std::move(video), {});
}

}  // namespace particles::render
