#include "render/gl_context.hpp"

#include <fmt/format.h>

#include <atomic>
#include <cstdlib>
#include <string>

#include "core/worker_pool.hpp"
#include "render/errors.hpp"
#include "render/frame_memory.hpp"
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

std::string frameSizeProblem(int width, int height, std::span<const GlSizeLimit> limits) {
  for (const GlSizeLimit& limit : limits) {
    if (limit.width <= 0 || limit.height <= 0) continue;  // not reported: nothing to check against
    if (width > limit.width || height > limit.height) {
      return fmt::format("a {}x{} frame is larger than this OpenGL draws: its {} is {}x{} pixels", width, height,
                         limit.name, limit.width, limit.height);
    }
  }
  return {};
}

GlSizeLimit GlContext::viewportLimit() const {
  GLint dims[2] = {0, 0};
  gl_.glGetIntegerv(GL_MAX_VIEWPORT_DIMS, dims);
  checkGl(gl_, "glGetIntegerv(GL_MAX_VIEWPORT_DIMS)");
  return {"GL_MAX_VIEWPORT_DIMS", dims[0], dims[1]};
}

void GlContext::reserveFrame(std::size_t glBytes) {
  const std::size_t imageBytes = frameBytes(width_, height_);
  const std::string what = fmt::format("a {}x{} frame ({} MiB for its image, {} MiB for the GL's buffers)", width_,
                                       height_, imageBytes >> 20, glBytes >> 20);
  MemoryReservation whole(imageBytes + glBytes, what);  // all of it at once first: one message for both
  whole = {};
  try {
    image_ = Image(width_, height_);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory(what + ": its image could not be allocated");
  }
  reservation_ = MemoryReservation(glBytes, what);
}

std::string GlContext::reservationNote() const {
  if (reservation_.bytes() == 0) return {};
  return fmt::format(" (with {} MiB held for the {}x{} frame's buffers: too little memory left for the GL itself?)",
                     reservation_.bytes() >> 20, width_, height_);
}

void GlContext::checkFrameSize(std::span<const GlSizeLimit> limits) const {
  if (const std::string problem = frameSizeProblem(width_, height_, limits); !problem.empty()) {
    throw FrameSizeError(fmt::format("{} ({})", problem, info_.renderer));
  }
}

void GlContext::beginFrame(Rgb bg, bool transparent) {
  makeCurrent();
  gl_.glViewport(0, 0, width_, height_);
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

void GlContext::startRead() {
  if (!readsAhead()) {
    finishFrame();
    return;
  }
  checkGl(gl_, "drawing the frame");
  readAhead();
}

const Image& GlContext::collectFrame() {
  if (!readsAhead()) return image_;
  makeCurrent();  // the frame loop may collect on another thread than it drew on
  collectAhead();
  return image_;
}

std::unique_ptr<GlContext> makeGlContext(const GlRequest& request, int width, int height) {
  validate(request);
  // Mesa keeps the threads of a display's rasteriser (llvmpipe's) from its first context on, and a
  // fork()ed child has none of them: the child's first frame waited for them forever. So a process
  // forked after GL was set up is refused a context, at once (the fork count: core/worker_pool.hpp).
  static std::atomic<long> firstContextAtFork{-1};
  long first = -1;
  if (!firstContextAtFork.compare_exchange_strong(first, long(forkCount())) && first != long(forkCount())) {
    throw RenderError(
        "no GL context can be made in a process forked after its parent set GL up: the GL driver's threads stayed "
        "in the parent. Draw here with the cpu raster (raster cpu, or auto without --gpu), or start this process "
        "fresh instead of by fork() (Python: multiprocessing's 'spawn' or 'forkserver')");
  }
  // LP_NUM_THREADS counts the threads besides the calling one: 0 rasterises on it.
  if (request.threads > 0 && std::getenv("LP_NUM_THREADS") == nullptr) {
    const std::string value = std::to_string(request.threads == 1 ? 0 : request.threads);
    setenv("LP_NUM_THREADS", value.c_str(), 0);
  }
#if PARTICLES_WITH_EGL
  if (request.backend == GlBackend::egl) return makeEglContext(request.gpu, request.readBack, width, height);
#endif
#if PARTICLES_WITH_OSMESA
  if (request.backend == GlBackend::osmesa) return makeOsMesaContext(width, height);
#endif
    // auto: EGL, else OSMesa. A GPU was asked for: EGL's hardware device or nothing (validate has
    // refused it without EGL), OSMesa would not be one.
#if PARTICLES_WITH_EGL && PARTICLES_WITH_OSMESA
  if (request.gpu) return makeEglContext(true, request.readBack, width, height);
  std::string eglFailure;
  try {
    return makeEglContext(false, request.readBack, width, height);
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
  return makeEglContext(request.gpu, request.readBack, width, height);
#else
  return makeOsMesaContext(width, height);
#endif
}

GlInfo probeGl(const GlRequest& request) {
  return makeGlContext(request, 1, 1)->info();
}

}  // namespace particles::render
