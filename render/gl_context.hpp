#pragma once
// Internal to render/: an off-screen OpenGL context drawing into an Image it owns, made by one of
// the backends of render/gl_backend.hpp (render/egl_context.hpp, render/osmesa_context.hpp). The
// frame's buffer is RGBA8 without depth, stencil or multisampling: shapes are drawn in painter's
// order and anti-aliased in the shader (render/renderer.hpp). Image row 0 is the top of the
// picture. Every context uses the same state, the same llvmpipe by default and the same storage
// order of rows (flipsY), so both backends give the same bytes.

#include <memory>
#include <string>

#include "render/gl_backend.hpp"
#include "render/gl_functions.hpp"
#include "render/image.hpp"
#include "render/theme.hpp"

namespace particles::render {

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

 protected:
  // The backend makes its context current, then calls loadFunctions.
  GlContext(int width, int height, bool flipsY) : image_(width, height), flipsY_(flipsY) {}
  // Looks the GL functions up in the now current context and records what it runs on.
  void loadFunctions(GlProcLookup lookup, const char* lookupName, GlBackend backend, std::string device);

  Image image_;  // the frame, top row first

 private:
  // Binds the context to this thread, really: a context the library believes current may not be,
  // when another backend has switched Mesa's dispatch in between. Throws RenderError.
  virtual void makeCurrent() = 0;
  // After everything is drawn: the backend's pixels into image_ (an OSMesa context draws there
  // already). Throws RenderError.
  virtual void readFrame() = 0;

  const bool flipsY_;
  GlFunctions gl_;
  GlInfo info_;
};

// The backend of `request` for a width × height frame, current on return; auto tries EGL, then
// OSMesa. Throws RenderError naming the failing call of every backend tried, and
// std::invalid_argument for a request this build cannot serve (validate).
std::unique_ptr<GlContext> makeGlContext(const GlRequest& request, int width, int height);

}  // namespace particles::render
