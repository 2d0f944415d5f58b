#pragma once
// Internal to render/: an off-screen OpenGL context drawing into an Image it owns, made by one of
// the backends of render/gl_backend.hpp (render/egl_context.hpp, render/osmesa_context.hpp). The
// frame's buffer is RGBA8 without depth, stencil or multisampling: shapes are drawn in painter's
// order and anti-aliased in the shader (render/renderer.hpp). Image row 0 is the top of the
// picture. Every context uses the same state, the same llvmpipe by default and the same storage
// order of rows (flipsY), so both backends give the same bytes.

#include <cstddef>
#include <memory>
#include <span>
#include <string>

#include "render/frame_memory.hpp"
#include "render/gl_backend.hpp"
#include "render/gl_functions.hpp"
#include "render/image.hpp"
#include "render/theme.hpp"

namespace particles::render {

// One of the GL implementation's limits on a frame's size, in pixels, e.g. {"GL_MAX_VIEWPORT_DIMS",
// 16384, 16384}.
struct GlSizeLimit {
  std::string name;
  int width = 0, height = 0;
};

// Empty when a width × height frame is within every limit (one of 0 × 0, not reported, is none);
// else which it exceeds, e.g. "a 16384x16384
// frame is wider than GL_MAX_RENDERBUFFER_SIZE allows (8192 pixels)".
std::string frameSizeProblem(int width, int height, std::span<const GlSizeLimit> limits);

class GlContext {
 public:
  virtual ~GlContext() = default;
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // The GL functions of this context; call them only while it is current (after beginFrame, or
  // right after it is made, which leaves it current).
  const GlFunctions& gl() const { return gl_; }
  const GlInfo& info() const { return info_; }
  // Whether the shader must put image row y at GL window row height − y rather than y: the row
  // order in which llvmpipe then stores and rasterises the picture is the one it uses for OSMesa's
  // buffer (render/egl_context.cpp says why that matters).
  bool flipsY() const { return flipsY_; }
  // Records why auto did not use EGL (GlInfo::fallback).
  void noteFallback(std::string reason) { info_.fallback = std::move(reason); }

  // Makes this context current (another renderer may have been drawing in between), sets the
  // state every frame is drawn with (coverage blended as alpha, nothing else) and clears the image
  // to `background`, or with `transparent` to nothing (0, 0, 0, 0): the image then holds colours
  // premultiplied by their alpha (the blending below is Porter–Duff "over" on premultiplied
  // colour). Throws RenderError.
  void beginFrame(Rgb background, bool transparent);
  // Waits until GL has drawn everything and returns the image. Throws RenderError if GL reported an
  // error since beginFrame.
  const Image& finishFrame();
  // The read-back in two steps, so that a frame loop draws frame k + 1 while frame k's pixels
  // travel. startRead, after the frame is drawn, asks GL to copy it into one of two
  // pixel-buffer objects and returns without waiting; collectFrame waits for the oldest copy
  // started and not yet collected and returns it as the image. At most two may be started and not
  // collected. Only where readsAhead (EGL); elsewhere startRead reads the frame at once
  // (finishFrame) and collectFrame returns it, so the frame must be collected before the next is
  // drawn. Both throw RenderError as finishFrame does.
  virtual bool readsAhead() const { return false; }
  void startRead();
  const Image& collectFrame();
  // Unbinds the context from this thread, where a backend binds a context to one thread at a time
  // (EGL): another thread may then draw with it. Between frames only.
  virtual void releaseFromThread() {}

 protected:
  // The backend calls reserveFrame first, then makes its context current, calls loadFunctions and
  // checkFrameSize, and releaseReservation right before it makes the frame's buffers.
  GlContext(int width, int height, bool flipsY) : width_(width), height_(height), flipsY_(flipsY) {}
  // Allocates the image and reserves the `glBytes` Mesa will allocate for the frame
  // (render/frame_memory.hpp), before the context exists. Throws OutOfMemory.
  void reserveFrame(std::size_t glBytes);
  void releaseReservation() { reservation_ = {}; }
  // For a failure to make the context while memory is held for the frame: " (with N MiB held for
  // the frame's buffers: too little memory left for the GL itself?)", or nothing.
  std::string reservationNote() const;
  // Looks the GL functions up in the now current context and records what it runs on.
  void loadFunctions(GlProcLookup lookup, const char* lookupName, GlBackend backend, std::string device);
  // Throws FrameSizeError when the frame is larger than one of `limits`.
  void checkFrameSize(std::span<const GlSizeLimit> limits) const;
  // GL_MAX_VIEWPORT_DIMS of the current context.
  GlSizeLimit viewportLimit() const;

  const int width_, height_;  // the frame's, in pixels
  Image image_;               // the frame, top row first; empty until reserveFrame

 private:
  // Binds the context to this thread, really: a context the library believes current may not be,
  // when another backend has switched Mesa's dispatch in between. Throws RenderError.
  virtual void makeCurrent() = 0;
  // After everything is drawn: the backend's pixels into image_ (an OSMesa context draws there
  // already). Throws RenderError.
  virtual void readFrame() = 0;
  // Where readsAhead: the frame into the next pixel buffer, without waiting; and the oldest such
  // frame out of its buffer into image_.
  virtual void readAhead() {}
  virtual void collectAhead() {}

  const bool flipsY_;
  MemoryReservation reservation_;
  GlFunctions gl_;
  GlInfo info_;
};

// The backend of `request` for a width × height frame, current on return; auto tries EGL, then
// OSMesa. Throws RenderError naming the failing call of every backend tried, and
// std::invalid_argument for a request this build cannot serve (validate).
std::unique_ptr<GlContext> makeGlContext(const GlRequest& request, int width, int height);

}  // namespace particles::render
