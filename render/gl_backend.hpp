#pragma once
// Which library makes the off-screen OpenGL context the renderer draws in (render/gl_context.hpp):
//   egl      EGL without a window: Mesa's software device (EGL_EXT_platform_device with the device
//            that has EGL_MESA_device_software), or its surfaceless platform when there is no
//            device list; drawn into a framebuffer object and read back. Mesa ≥ 25.1 has only this.
//   osmesa   OSMesa, Mesa's off-screen library (removed in Mesa 25.1), drawing into our memory.
//   auto     EGL when it starts, else OSMesa.
// Both run llvmpipe, Mesa's software rasteriser, by default, so frames are the same bytes on every
// machine and through either backend (tests/test_render_backends.cpp). `gpu` asks EGL for a
// hardware device instead; there is no fallback from it.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <particles/choices.hpp>

namespace particles::render {

using GlBackend = particles::GlBackend;  // include/particles/choices.hpp

struct GlRequest {
  GlBackend backend = GlBackend::automatic;
  bool gpu = false;  // a hardware EGL device rather than the software one
  // The threads llvmpipe may rasterise on, counting the calling thread: 1 rasterises on it alone,
  // 0 leaves Mesa's default (one thread per online CPU, up to 16). Mesa reads it from the
  // environment (LP_NUM_THREADS) when it makes its first context in the process, so the first
  // request's count holds for the process; an LP_NUM_THREADS the user set wins. llvmpipe's pixels
  // do not depend on it (golden/README.md: the same bytes with 0, 1, 2 and 8).
  int threads = 0;
  // How EGL reads frames back (GlContext::startRead): ahead, through two pixel-pack buffers, which
  // pays on a GPU (the copy runs while the next frame is drawn); or at once. automatic: ahead with
  // `gpu`. On llvmpipe the copy is made at once either way, and the buffers' extra copy cost the
  // demo's render 2 to 3 % (bench/README.md, "The resident path"). OSMesa draws into the image.
  enum class ReadBack { automatic, ahead, direct };
  ReadBack readBack = ReadBack::automatic;
};

// "auto", "egl", "osmesa", and back; nothing for another name.
std::string_view glBackendName(GlBackend backend);
std::optional<GlBackend> glBackendFromName(std::string_view name);
std::vector<std::string> glBackendNames();

// Whether this build has the backend (CMake's PARTICLES_WITH_EGL, PARTICLES_WITH_OSMESA); auto: always.
bool glBackendBuilt(GlBackend backend);
// "EGL and OSMesa", "EGL only (built with -DPARTICLES_WITH_OSMESA=OFF)", …: for messages.
std::string glBuildDescription();

// Throws std::invalid_argument for a request this build cannot serve: a backend it lacks, or
// `gpu` with OSMesa or without EGL.
void validate(const GlRequest& request);

// What a context runs on.
struct GlInfo {
  // false where no context was made: the cpu raster path draws without GL (render/renderer.hpp),
  // and the fields below are empty.
  bool made = true;
  GlBackend backend = GlBackend::automatic;  // egl or osmesa once made
  std::string device;    // "software device", "surfaceless platform", "hardware device /dev/dri/…", …
  std::string renderer;  // GL_RENDERER, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)"
  std::string version;   // GL_VERSION, e.g. "4.5 (Compatibility Profile) Mesa 22.3.6"
  std::string fallback;  // auto only: why EGL was not used; empty when it was
};

// "egl, software device: llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Compatibility Profile) Mesa 22.3.6"
// and, after an automatic fallback, "(EGL: REASON)"; where no context was made, "none (the cpu raster)".
std::string describe(const GlInfo& info);

// Makes a 1 × 1 context as the renderer would and says what it runs on. Throws RenderError when
// none can be made (the message names every backend tried), std::invalid_argument as validate.
GlInfo probeGl(const GlRequest& request);

}  // namespace particles::render
