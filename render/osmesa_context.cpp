#include "render/osmesa_context.hpp"

#include <GL/osmesa.h>
#include <fmt/format.h>

#include <cstdint>

#include "render/errors.hpp"
#include "render/frame_memory.hpp"

namespace particles::render {

namespace {

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height);

 private:
  struct ContextDeleter {
    // Destroying the context frees the shader program with it.
    void operator()(osmesa_context* context) const { OSMesaDestroyContext(context); }
  };
  std::unique_ptr<osmesa_context, ContextDeleter> context_;
  std::uint8_t probePixel_[4] = {};  // the 1 × 1 buffer the context is first made current with

  void makeCurrent() override;
  void readFrame() override;
};

OsMesaContext::OsMesaContext(int width, int height) : GlContext(width, height, false) {
  // Mesa's colour buffer, which OSMesaMakeCurrent allocates and glFinish copies into ours: when
  // its allocation failed, that copy was a SIGSEGV (render/frame_memory.hpp).
  reserveFrame(frameBytes(width, height));
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         0,
                         OSMESA_STENCIL_BITS,
                         0,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_COMPAT_PROFILE,
                         0};
  context_.reset(OSMesaCreateContextAttribs(attribs, nullptr));
  if (!context_) {
    throw RenderError(
        "OSMesaCreateContextAttribs(OSMESA_RGBA, compatibility profile) failed: Mesa could not make an off-screen "
        "OpenGL context (is libOSMesa's software rasteriser, llvmpipe or softpipe, installed?)" +
        reservationNote());
  }
  // First current on a 1 × 1 buffer: the limits are asked for before Mesa allocates the frame's.
  if (!OSMesaMakeCurrent(context_.get(), probePixel_, GL_UNSIGNED_BYTE, 1, 1)) {
    throw RenderError("OSMesaMakeCurrent(1x1, GL_UNSIGNED_BYTE) failed");
  }
  // Image row 0 must be the top of the picture: with OSMESA_Y_UP = 1 (the default) memory row 0 is
  // GL window row 0, and the shader puts the top of the view there (flipsY false). Mesa stores the
  // buffer the other way up (a window-system buffer) and copies it into ours at glFinish.
  OSMesaPixelStore(OSMESA_Y_UP, 1);
  loadFunctions(OSMesaGetProcAddress, "OSMesaGetProcAddress", GlBackend::osmesa, "off-screen buffer");
  GLint maxWidth = 0, maxHeight = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &maxWidth);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &maxHeight);
  const GlSizeLimit limits[] = {{"OSMESA_MAX_WIDTH × OSMESA_MAX_HEIGHT", maxWidth, maxHeight}, viewportLimit()};
  checkFrameSize(limits);
  releaseReservation();
  makeCurrent();
}

void OsMesaContext::makeCurrent() {
  // OSMesaMakeCurrent always binds, whatever was current before (an EGL context included).
  if (!OSMesaMakeCurrent(context_.get(), image_.rgba.data(), GL_UNSIGNED_BYTE, image_.width, image_.height)) {
    throw RenderError(fmt::format("OSMesaMakeCurrent({}x{}, GL_UNSIGNED_BYTE) failed", image_.width, image_.height));
  }
}

void OsMesaContext::readFrame() {
  gl().glFinish();
  checkGl(gl(), "glFinish");
}

}  // namespace

std::unique_ptr<GlContext> makeOsMesaContext(int width, int height) {
  return std::make_unique<OsMesaContext>(width, height);
}

}  // namespace particles::render
