#pragma once
/// @file
/// Frames to a video: MP4 (H.264), WebM (VP9) or GIF, by the path's extension, written as
/// `particles render -o` writes them: under a temporary name, moved into place by finish(). A
/// writer destroyed, or stopped by abort(), before finish() leaves nothing, and an existing file of
/// that name untouched.
///
/// @code
/// particles::VideoWriter video("cloth.mp4", {.fps = 30});
/// for (int i = 0; i < 60; ++i) { video.write(renderer.render(sim)); sim.advance(1.0 / 30); }
/// video.finish();   // the frames of `particles render cloth.yaml --fps 30 --duration 2`
/// @endcode

#include <memory>
#include <string>

#include <particles/export.hpp>
#include <particles/renderer.hpp>

namespace particles {

/// What `particles render` takes for a video besides its frames; the names are its options'.
struct VideoSettings {
  /// Frames per second of the video, 1 to 1000 (GIF: 1 to 50); 0: the format's default, as
  /// `particles render` takes it: 60, and 30 for GIF.
  int fps = 0;
  int crf = -1;                  ///< quality (the encoder's constant rate factor); −1: the format's default
  std::string preset = "medium"; ///< MP4's x264 preset: ultrafast … placebo
  double keyintSeconds = 2.0;    ///< the longest time between keyframes, s
  bool alpha = false;            ///< keep the frames' alpha (WebM only): frames drawn over a transparent background
  /// The encoders' own report on stderr (x264's settings and statistics). libav's log level is the
  /// process's: a writer made with `verbose` turns it on for every writer, and one without off.
  bool verbose = false;
};

/// Writes frames to an MP4, WebM or GIF file (chosen by the path's extension), encoded as
/// `particles render` encodes them: whole, or nothing. Moved, never copied.
class PARTICLES_API VideoWriter {
 public:
  /// Checks the path's format and the settings (ArgumentError naming what is wrong); the file is
  /// opened at the first frame, whose size every frame must then have (MP4 and WebM: even sides;
  /// MP4 at most 16384 px a side).
  VideoWriter(const std::string& path, const VideoSettings& settings = {});
  /// Takes over other's file and frames; other may then only be destroyed or assigned to.
  VideoWriter(VideoWriter&& other) noexcept;
  /// Aborts this writer's own video, then takes over other's file and frames.
  VideoWriter& operator=(VideoWriter&& other) noexcept;
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;
  /// Without finish(): as abort().
  ~VideoWriter();

  /// Queues one frame for the encoder (copied). Throws ArgumentError for a frame of another size or
  /// malformed, or after abort(); OutputError when the file cannot be written (the writer is then
  /// aborted).
  void write(const Image& frame);
  /// Encodes what is queued and moves the video into place. Throws OutputError; ArgumentError after
  /// abort() or before any frame.
  void finish();
  /// Stops and removes everything written so far; later write() and finish() calls are refused.
  /// Never throws; does nothing after finish(). Safe from another thread while write() or finish()
  /// runs: it waits for that call to end, then stops (a finish() that completed has its file).
  /// In a child of fork(), a writer made before the fork refuses write() and finish() (Error), and
  /// abort() leaves it to the parent.
  void abort() noexcept;
  long frames() const;  ///< frames written so far

  struct Impl;  ///< the library's own, opaque here

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace particles
