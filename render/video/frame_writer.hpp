#pragma once
// Where rendered frames go (`particles render SCENARIO -o OUT`, docs/physics.md §12): a writer for
// each format of render/video/output_formats.hpp that is a run of frames, opened by openFrameWriter from
// the format's row. The one frame at --at T is not a stream: renderSimulation calls writePng
// (png_io.hpp) directly.
//
// A writer encodes on its own thread behind a bounded queue, writes to a temporary (an anonymous
// file, or the staging directory of a PNG sequence) and moves the result into place in finish(). Until then an existing
// output is untouched; abort(), an error, or destroying an unfinished writer removes everything it wrote.
//
// Interruption (SIGINT/SIGTERM). abort() is not async-signal-safe (it joins a thread and frees
// codec state), so the signal handler only sets a flag that the frame loop polls:
//
//   volatile std::sig_atomic_t stopRequested = 0;        // file scope in the CLI
//   void onSignal(int) { stopRequested = 1; }
//   ...
//   std::signal(SIGINT, onSignal); std::signal(SIGTERM, onSignal);
//   auto writer = openFrameWriter(out, options);
//   for (long i = 0; i < frames; ++i) {
//     if (stopRequested) { writer->abort(); return 130; }   // partial output removed
//     advance the system to t = i / fps;
//     writer->write(renderer.render(system.draw(), camera));
//   }
//   writer->finish();
//
// write() returns within about one frame's encoding time, so the flag is seen promptly. A signal
// during finish() (the trailer, the +faststart rewrite and the rename) is seen after it returns,
// when the output is already complete. Letting the writer go out of scope (an exception unwinding
// the loop) has the same effect as abort().

#include <array>
#include <cstddef>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "core/drawing.hpp"
#include "render/image.hpp"
#include "render/video/output_formats.hpp"
#include "render/png_io.hpp"

namespace particles::render {

class FrameWriter {
 public:
  virtual ~FrameWriter() = default;
  // Queues one frame (copied); blocks while the queue is full. Every frame must have the size
  // the writer was opened with. Rethrows an encoding error from the worker (the writer is then
  // aborted: its temporary output is already gone).
  virtual void write(const Image& frame) = 0;
  // Encodes what is queued, finalises the file(s) and moves them into place. Throws OutputError.
  virtual void finish() = 0;
  // Stops encoding and removes everything written so far. Never throws; idempotent.
  virtual void abort() noexcept = 0;
  virtual const std::filesystem::path& destination() const = 0;
  virtual long framesWritten() const = 0;  // frames accepted by write()
};

struct VideoOptions {
  int fps = 60;
  // Constant rate factor (quality) of the encoder, in the range of its format's row
  // (render/video/output_formats.hpp; crfOf). Nothing: the row's default.
  std::optional<int> crf;
  // x264 preset: ultrafast … placebo (kX264Presets). veryfast encodes about twice as fast as
  // medium, for slightly larger files (bench/README.md, "x264 preset").
  std::string preset = "medium";
  // x264 tune, "" for none. "animation" sounds right for line art but measured worse on the cloth:
  // larger files and no faster than none (bench/README.md, "x264 tune").
  std::string tune;
  // Longest time between keyframes, s: a web player seeks to the keyframe before the time asked
  // for and decodes on from there, so 2 s keeps scrubbing quick. x264's default, 250 frames, is
  // 4.2 s at 60 fps. x264 may put keyframes closer together, at scene cuts. In frames:
  // keyframeInterval().
  double keyintSeconds = 2.0;
  // round(keyintSeconds · fps), at least 1.
  int keyframeInterval() const;
  // x264's threads; 0: its default, 1.5 per CPU the process may use. x264 is deterministic for a
  // given count, and the settings note it leaves in the first frame (an SEI message, "threads=N")
  // says how many ran. Its pictures are the same for 1 to 3 threads; beyond, each frame thread's
  // vertical motion search is held to the rows the threads before it have encoded (x264's
  // mv-range-thread, shorter with more threads), so pictures may differ (docs/cli.md,
  // "Threads"). VP9 keeps a fixed count (webm_writer.cpp): libvpx's pictures depend on it.
  int encoderThreads = 0;
};
// The largest --keyint, s: an hour.
inline constexpr double kMaxKeyintSeconds = 3600.0;
// The frame rates every output takes (render --fps, whole frames a second; the video writers check
// them again): from 1 to particles::kMaxFps (core/drawing.hpp), a scenario's largest render.fps.
inline constexpr int kMinFps = 1;
using particles::kMaxFps;

// The names x264 accepts as --preset, fastest first (x264 --fullhelp). The help shows the range
// up to veryslow: placebo, the last, costs far more for no visible gain.
inline constexpr std::array<std::string_view, 10> kX264Presets = {
    "ultrafast", "superfast", "veryfast", "faster", "fast", "medium", "slow", "slower", "veryslow", "placebo"};

// True for the names x264 accepts as --preset (kX264Presets).
bool isX264Preset(const std::string& name);

struct FrameWriterOptions {
  int width = 1280;  // every frame must have this size
  int height = 720;
  VideoOptions video;
  PngOptions png;  // png.alpha: RGBA frames in a PNG sequence
  // The frames have alpha to keep (a transparent background): WebM as yuva420p, PNG as RGBA.
  bool alpha = false;
  // Frames waiting for the encoder. Two to four are enough to keep renderer and encoder busy;
  // more only costs memory (3.7 MB per 1280×720 frame). 0: no encoder thread, each frame is
  // encoded on the calling thread as it is written (a render held to one thread).
  size_t queueFrames = 4;
  // A PNG sequence: the index in the whole render of the first frame written (its file name), and
  // whether this is the whole render, whose finish() removes frame files of an earlier, longer run.
  // A range (RenderJob::frames) writes its own frames only.
  long firstIndex = 0;
  bool wholeSequence = true;
};

// Opens the writer of the path's format (outputFormatOf). Throws std::invalid_argument for a path
// of no format, or of the one-frame PNG (use writePng), for alpha (FrameWriterOptions::alpha) the
// format cannot keep, and for bad options (including an odd size for MP4 and WebM, see
// yuv_video_writer.hpp, or an fps GIF cannot show); OutputError if the output cannot be created
// (the message names the path and the reason).
std::unique_ptr<FrameWriter> openFrameWriter(const std::filesystem::path& path, const FrameWriterOptions& options);

// Frames for `duration` seconds at `fps`: at t = i / fps for i = 0 … frameCount − 1, so that the
// video lasts frameCount / fps = duration (rounded to whole frames, at least one).
long frameCount(double duration, int fps);

// libav's own logging (x264 prints its settings and statistics at "info"). Process-wide, because
// libav's log level is; the command line sets it once from --quiet/--verbose.
void setLibavVerbose(bool verbose);

}  // namespace particles::render
