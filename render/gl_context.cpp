#include "render/gl_context.hpp"

#include <fmt/format.h>

#include "render/errors.hpp"
#if PARTICLES_WITH_EGL
#include "render/egl_context.hpp"
#endif
#if PARTICLES_WITH_OSMESA
#include "render/osmesa_context.hpp"
#endif

namespace particles::render {

void GlContext::loadFunctions(GlProcLookup lookup, const char* lookupName, GlBackend backend, std::string device) {
  gl_ = loadGlFunctions(lookup, lookupName);
  info_.backend = backend;
  info_.device = std::move(device);
  info_.renderer = glString(gl_, GL_RENDERER);
  info_.version = glString(gl_, GL_VERSION);
}

void GlContext::beginFrame(Rgb bg, bool transparent) {
  makeCurrent();
  gl_.glViewport(0, 0, image_.width, image_.height);
  gl_.glDisable(GL_DEPTH_TEST);
  gl_.glDisable(GL_CULL_FACE);
  gl_.glDisable(GL_DITHER);
  gl_.glDisable(GL_MULTISAMPLE);
  // Coverage a as alpha over what is drawn (render/shader_program.hpp): colour c·a + d·(1 − a), alpha
  // a + d_a·(1 − a). Over an opaque background the destination keeps alpha 1. Over a transparent one
  // (cleared to 0) this is "over" with the destination premultiplied: d holds colour × d_a.
  gl_.glEnable(GL_BLEND);
  gl_.glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  if (transparent) {
    gl_.glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
  } else {
    gl_.glClearColor(float(bg.r) / 255.0f, float(bg.g) / 255.0f, float(bg.b) / 255.0f, 1.0f);
  }
  gl_.glClear(GL_COLOR_BUFFER_BIT);
}

const Image& GlContext::finishFrame() {
  checkGl(gl_, "drawing the frame");
  readFrame();
  return image_;
}

std::unique_ptr<GlContext> makeGlContext(const GlRequest& request, int width, int height) {
  validate(request);
#if PARTICLES_WITH_EGL
  if (request.backend == GlBackend::egl) return makeEglContext(request.gpu, width, height);
#endif
#if PARTICLES_WITH_OSMESA
  if (request.backend == GlBackend::osmesa) return makeOsMesaContext(width, height);
#endif
    // auto: EGL, else OSMesa. A GPU was asked for: EGL's hardware device or nothing (validate has
    // refused it without EGL), OSMesa would not be one.
#if PARTICLES_WITH_EGL && PARTICLES_WITH_OSMESA
  if (request.gpu) return makeEglContext(true, width, height);
  std::string eglFailure;
  try {
    return makeEglContext(false, width, height);
  } catch (const RenderError& e) {
    eglFailure = e.what();
  }
  try {
    auto context = makeOsMesaContext(width, height);
    context->noteFallback(eglFailure);
    return context;
  } catch (const RenderError& e) {
    throw RenderError(fmt::format("no OpenGL context could be made. EGL: {}. OSMesa: {}", eglFailure, e.what()));
  }
#elif PARTICLES_WITH_EGL
  return makeEglContext(request.gpu, width, height);
#else
  return makeOsMesaContext(width, height);
#endif
}

GlInfo probeGl(const GlRequest& request) {
  return makeGlContext(request, 1, 1)->info();
}

}  // namespace particles::render
