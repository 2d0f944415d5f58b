#include "render/osmesa_context.hpp"

#include <GL/osmesa.h>
#include <fmt/format.h>

#include <dlfcn.h>

#include <cstdint>
#include <string>
#include <type_traits>

#include "render/errors.hpp"
#include "render/frame_memory.hpp"

namespace particles::render {

namespace {

// libOSMesa, opened when the first OSMesa context is made rather than linked: it brings LLVM and
// some thirty other libraries, which every start of the program paid for when linked, though the
// cpu path and EGL never use it. Opened once for the process and never closed (Mesa keeps state
// for the process); its functions are those of <GL/osmesa.h>, by their declared types.
struct OsMesaLibrary {
  decltype(&OSMesaCreateContextAttribs) createContextAttribs = nullptr;
  decltype(&OSMesaDestroyContext) destroyContext = nullptr;
  decltype(&OSMesaMakeCurrent) makeCurrent = nullptr;
  decltype(&OSMesaPixelStore) pixelStore = nullptr;
  decltype(&OSMesaGetIntegerv) getIntegerv = nullptr;
  decltype(&OSMesaGetProcAddress) getProcAddress = nullptr;
  std::string error;  // why it could not be opened; empty when it was
};

OsMesaLibrary openOsMesa() {
  OsMesaLibrary library;
  void* handle = ::dlopen(PARTICLES_OSMESA_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    const char* why = ::dlerror();
    library.error = fmt::format("OSMesa's library {} could not be loaded ({}): install Mesa's OSMesa (Debian: "
                                "libosmesa6), or use EGL (--gl egl)",
                                PARTICLES_OSMESA_SONAME, why ? why : "no reason given");
    return library;
  }
  std::string missing;
  const auto find = [&](auto& function, const char* name) {
    function = reinterpret_cast<std::remove_reference_t<decltype(function)>>(::dlsym(handle, name));
    if (!function) missing += missing.empty() ? name : std::string(", ") + name;
  };
  find(library.createContextAttribs, "OSMesaCreateContextAttribs");
  find(library.destroyContext, "OSMesaDestroyContext");
  find(library.makeCurrent, "OSMesaMakeCurrent");
  find(library.pixelStore, "OSMesaPixelStore");
  find(library.getIntegerv, "OSMesaGetIntegerv");
  find(library.getProcAddress, "OSMesaGetProcAddress");
  if (!missing.empty()) {
    library.error = fmt::format("OSMesa's library {} lacks {}", PARTICLES_OSMESA_SONAME, missing);
  }
  return library;
}

// The library, opened on the first call (thread-safe); throws RenderError when it cannot be.
const OsMesaLibrary& osMesa() {
  static const OsMesaLibrary library = openOsMesa();
  if (!library.error.empty()) throw RenderError(library.error);
  return library;
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int width, int height);

 private:
  struct ContextDeleter {
    // Destroying the context frees the shader program with it.
    void operator()(osmesa_context* context) const { osMesa().destroyContext(context); }
  };
  std::unique_ptr<osmesa_context, ContextDeleter> context_;
  std::uint8_t probePixel_[4] = {};  // the 1 × 1 buffer the context is first made current with

  void makeCurrent() override;
  void readFrame() override;
};

OsMesaContext::OsMesaContext(int width, int height) : GlContext(width, height, false) {
  const OsMesaLibrary& osmesa = osMesa();
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
  context_.reset(osmesa.createContextAttribs(attribs, nullptr));
  if (!context_) {
    throw RenderError(
        "OSMesaCreateContextAttribs(OSMESA_RGBA, compatibility profile) failed: Mesa could not make an off-screen "
        "OpenGL context (is libOSMesa's software rasteriser, llvmpipe or softpipe, installed?)" +
        reservationNote());
  }
  // First current on a 1 × 1 buffer: the limits are asked for before Mesa allocates the frame's.
  if (!osmesa.makeCurrent(context_.get(), probePixel_, GL_UNSIGNED_BYTE, 1, 1)) {
    throw RenderError("OSMesaMakeCurrent(1x1, GL_UNSIGNED_BYTE) failed");
  }
  // Image row 0 must be the top of the picture: with OSMESA_Y_UP = 1 (the default) memory row 0 is
  // GL window row 0, and the shader puts the top of the view there (flipsY false). Mesa stores the
  // buffer the other way up (a window-system buffer) and copies it into ours at glFinish.
  osmesa.pixelStore(OSMESA_Y_UP, 1);
  loadFunctions(osmesa.getProcAddress, "OSMesaGetProcAddress", GlBackend::osmesa, "off-screen buffer");
  GLint maxWidth = 0, maxHeight = 0;
  osmesa.getIntegerv(OSMESA_MAX_WIDTH, &maxWidth);
  osmesa.getIntegerv(OSMESA_MAX_HEIGHT, &maxHeight);
  const GlSizeLimit limits[] = {{"OSMESA_MAX_WIDTH × OSMESA_MAX_HEIGHT", maxWidth, maxHeight}, viewportLimit()};
  checkFrameSize(limits);
  releaseReservation();
  makeCurrent();
}

void OsMesaContext::makeCurrent() {
  // OSMesaMakeCurrent always binds, whatever was current before (an EGL context included).
  if (!osMesa().makeCurrent(context_.get(), image_.rgba.data(), GL_UNSIGNED_BYTE, image_.width, image_.height)) {
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
