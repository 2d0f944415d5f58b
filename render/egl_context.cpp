#include "render/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "render/errors.hpp"
#include "render/frame_memory.hpp"

namespace particles::render {

namespace {

std::string eglErrorName(EGLint e) {
  switch (e) {
    case EGL_SUCCESS: return "EGL_SUCCESS";
    case EGL_NOT_INITIALIZED: return "EGL_NOT_INITIALIZED";
    case EGL_BAD_ACCESS: return "EGL_BAD_ACCESS";
    case EGL_BAD_ALLOC: return "EGL_BAD_ALLOC";
    case EGL_BAD_ATTRIBUTE: return "EGL_BAD_ATTRIBUTE";
    case EGL_BAD_CONFIG: return "EGL_BAD_CONFIG";
    case EGL_BAD_CONTEXT: return "EGL_BAD_CONTEXT";
    case EGL_BAD_CURRENT_SURFACE: return "EGL_BAD_CURRENT_SURFACE";
    case EGL_BAD_DISPLAY: return "EGL_BAD_DISPLAY";
    case EGL_BAD_MATCH: return "EGL_BAD_MATCH";
    case EGL_BAD_PARAMETER: return "EGL_BAD_PARAMETER";
    case EGL_BAD_SURFACE: return "EGL_BAD_SURFACE";
    case EGL_CONTEXT_LOST: return "EGL_CONTEXT_LOST";
    case EGL_BAD_DEVICE_EXT: return "EGL_BAD_DEVICE_EXT";
    default: return fmt::format("0x{:04x}", e);
  }
}

// Throws RenderError("CALL failed: EGL_ERROR" and what it usually means).
[[noreturn]] void failEgl(std::string_view call, std::string_view advice = {}) {
  const std::string error = eglErrorName(eglGetError());
  throw RenderError(advice.empty() ? fmt::format("{} failed: {}", call, error)
                                   : fmt::format("{} failed: {} ({})", call, error, advice));
}

// Whether the space-separated `list` (may be null) names `extension`.
bool hasExtension(const char* list, std::string_view extension) {
  for (std::string_view rest = list ? list : ""; !rest.empty();) {
    const size_t end = rest.find(' ');
    if (rest.substr(0, end) == extension) return true;
    if (end == std::string_view::npos) break;
    rest.remove_prefix(end + 1);
  }
  return false;
}

// llvmpipe and softpipe by their GL_RENDERER ("llvmpipe (LLVM 15.0.6, 256 bits)"), Mesa's classic
// software rasteriser by its own.
bool isSoftwareRenderer(std::string_view renderer) {
  return renderer.starts_with("llvmpipe") || renderer.starts_with("softpipe") ||
         renderer.find("Software Rasterizer") != std::string_view::npos;
}

// The client extensions that find a display without a window system, looked up in EGL.
struct EglPlatforms {
  PFNEGLGETPLATFORMDISPLAYEXTPROC getPlatformDisplay = nullptr;
  PFNEGLQUERYDEVICESEXTPROC queryDevices = nullptr;
  PFNEGLQUERYDEVICESTRINGEXTPROC queryDeviceString = nullptr;
  bool deviceList = false;   // EGL_EXT_platform_device, EGL_EXT_device_enumeration, EGL_EXT_device_query
  bool surfaceless = false;  // EGL_MESA_platform_surfaceless
  std::string extensions;    // for messages
};

EglPlatforms eglPlatforms() {
  EglPlatforms p;
  const char* client = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);  // null: no client extensions
  p.extensions = client && *client ? client : "none";
  p.getPlatformDisplay =
      reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(eglGetProcAddress("eglGetPlatformDisplayEXT"));
  p.queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  p.queryDeviceString = reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  const bool platforms = hasExtension(client, "EGL_EXT_platform_base") && p.getPlatformDisplay;
  p.deviceList = platforms && hasExtension(client, "EGL_EXT_platform_device") &&
                 (hasExtension(client, "EGL_EXT_device_enumeration") || hasExtension(client, "EGL_EXT_device_base")) &&
                 p.queryDevices && p.queryDeviceString;
  p.surfaceless = platforms && hasExtension(client, "EGL_MESA_platform_surfaceless");
  return p;
}

// Initialises `display` (again: then nothing happens, EGL 1.5 §3.2) and returns it. Displays are
// never terminated: EGL has one display per device in the process, and eglTerminate would end
// every other renderer's context on it; it also unloads Mesa's DRI driver, whose llvmpipe keeps
// state it never frees (as OSMesa's does, tests/lsan.supp), after which LeakSanitizer cannot say
// whose it was. Mesa releases displays at exit.
EGLDisplay initialize(EGLDisplay display) {
  EGLint major = 0, minor = 0;
  if (!eglInitialize(display, &major, &minor)) {
    failEgl("eglInitialize", "no driver for the device? Mesa's llvmpipe is Debian's libgl1-mesa-dri");
  }
  return display;
}

// The display to draw on, and what to call it.
struct DisplayChoice {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string device;
  bool mesaChose = false;  // the surfaceless platform: Mesa picked the device, check its renderer
};

std::string deviceFile(const EglPlatforms& egl, EGLDeviceEXT device, const char* extensions) {
  const char* file = nullptr;
  if (hasExtension(extensions, "EGL_EXT_device_drm_render_node")) {
    file = egl.queryDeviceString(device, EGL_DRM_RENDER_NODE_FILE_EXT);
  }
  if (!file && hasExtension(extensions, "EGL_EXT_device_drm"))
    file = egl.queryDeviceString(device, EGL_DRM_DEVICE_FILE_EXT);
  return file ? file : "(no device file)";
}

// The devices EGL lists; none where it has no device list.
std::vector<EGLDeviceEXT> listDevices(const EglPlatforms& egl) {
  if (!egl.deviceList) return {};
  EGLint count = 0;
  if (!egl.queryDevices(0, nullptr, &count)) failEgl("eglQueryDevicesEXT");
  std::vector<EGLDeviceEXT> devices(size_t(std::max(count, 0)));
  if (count > 0 && !egl.queryDevices(count, devices.data(), &count)) failEgl("eglQueryDevicesEXT");
  devices.resize(size_t(std::max(count, 0)));
  return devices;
}

DisplayChoice chooseDisplay(bool gpu) {
  const EglPlatforms egl = eglPlatforms();
  const std::vector<EGLDeviceEXT> devices = listDevices(egl);
  for (EGLDeviceEXT device : devices) {
    const char* extensions = egl.queryDeviceString(device, EGL_EXTENSIONS);
    const bool software = hasExtension(extensions, "EGL_MESA_device_software");
    if (software == gpu) continue;
    const EGLDisplay display = egl.getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, device, nullptr);
    if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT)");
    return {display, software ? "software device" : "hardware device " + deviceFile(egl, device, extensions)};
  }
  if (gpu && egl.deviceList) {
    // The surfaceless platform would look at the same DRM devices: nothing more to try.
    throw RenderError(fmt::format(
        "a GPU was asked for, but EGL lists no hardware device ({} device{}, all software rasterisers). A GPU "
        "needs its driver's EGL (Mesa's for AMD and Intel, NVIDIA's own) and access to /dev/dri/renderD*; "
        "without --gpu, frames are drawn on the CPU",
        devices.size(), devices.size() == 1 ? "" : "s"));
  }
  if (egl.surfaceless) {
    const EGLDisplay display = egl.getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) failEgl("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    return {display, "surfaceless platform", true};
  }
  const std::string listed =
      egl.deviceList
          ? fmt::format("EGL lists {} device{}, none of them {}", devices.size(), devices.size() == 1 ? "" : "s",
                        gpu ? "hardware" : "Mesa's software rasteriser (EGL_MESA_device_software)")
          : std::string("EGL lists no devices (no EGL_EXT_platform_device with EGL_EXT_device_enumeration)");
  throw RenderError(
      fmt::format("{}, and has no EGL_MESA_platform_surfaceless (its client extensions: {}). Mesa's EGL has both "
                  "(Debian: libegl-mesa0, with llvmpipe in libgl1-mesa-dri)",
                  listed, egl.extensions));
}

// A context, released and destroyed with this object (with the framebuffer and shader program made
// in it).
class OwnedContext {
 public:
  explicit OwnedContext(EGLDisplay display) : display_(display) {
    if (!eglBindAPI(EGL_OPENGL_API)) failEgl("eglBindAPI(EGL_OPENGL_API)", "this EGL has no desktop OpenGL");
    // Any config that renders OpenGL: the context draws into a framebuffer object, not a surface.
    const EGLint wanted[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, 0, EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configs = 0;
    if (!eglChooseConfig(display_, wanted, &config, 1, &configs)) failEgl("eglChooseConfig(OpenGL)");
    if (configs == 0) throw RenderError("eglChooseConfig(OpenGL) found no config: this EGL device cannot draw OpenGL");
    // GLSL 1.30 and framebuffer objects need OpenGL 3.0; client-side vertex arrays and gl_FragColor
    // (render/shader_program.cpp) the compatibility profile, as OSMesa's context has.
    const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                              3,
                              EGL_CONTEXT_MINOR_VERSION,
                              0,
                              EGL_CONTEXT_OPENGL_PROFILE_MASK,
                              EGL_CONTEXT_OPENGL_COMPATIBILITY_PROFILE_BIT,
                              EGL_NONE};
    context_ = eglCreateContext(display_, config, EGL_NO_CONTEXT, attribs);
    if (context_ == EGL_NO_CONTEXT) failEgl("eglCreateContext(OpenGL 3.0, compatibility profile)");
  }
  ~OwnedContext() {
    release();
    eglDestroyContext(display_, context_);
  }
  OwnedContext(const OwnedContext&) = delete;
  OwnedContext& operator=(const OwnedContext&) = delete;

  // Binds the context, without a surface, to this thread. OSMesa switches Mesa's GL dispatch to
  // its own context without EGL knowing, and EGL does not bind again a context it believes
  // current (seen with GLVND and Mesa 22.3: the frame was drawn in the OSMesa context): release
  // it first. A release and a bind cost little beside a frame (bench/README.md, "EGL context per frame").
  void makeCurrent() {
    release();
    if (!eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_)) {
      failEgl("eglMakeCurrent(no surface)", "a context without a surface needs EGL_KHR_surfaceless_context");
    }
  }

  // Unbinds the context if it is this thread's.
  void release() {
    if (eglGetCurrentContext() == context_) {
      eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    }
  }

 private:
  EGLDisplay display_;
  EGLContext context_ = EGL_NO_CONTEXT;
};

// The frame is drawn upside down into a framebuffer object (flipsY), the row order in which Mesa
// stores OSMesa's window-system buffer; llvmpipe rasterises in storage order, and where an edge
// passes exactly through a pixel centre or a sample position the order decides whether the sample
// is in. Drawn upright, 2 pixels of golden/cloth_t2.5.png (the cursor's tip) differed from
// OSMesa's by 59 at 4 samples, and at 1 and 16 samples a whole row of the cloth's rail, whose edge
// lies on pixel centres; an EGL pbuffer (a window-system buffer too) still differed on the rail.
// Upside down, every frame tried is the same bytes as OSMesa's (tests/test_render_backends.cpp).
// The most glReadPixels is asked for at once: its scratch memory is this, not a frame (a 16384²
// frame is 1 GiB), and a frame of 1280 × 720 (3.5 MiB) or 4K (32 MiB) is still read in one call.
constexpr std::size_t kReadStripBytes = std::size_t(32) << 20;

class EglContext final : public GlContext {
 public:
  EglContext(bool gpu, bool readAhead, int width, int height);
  void releaseFromThread() override { context_->release(); }
  bool readsAhead() const override { return readAhead_; }

 private:
  std::unique_ptr<OwnedContext> context_;
  bool packInvert_ = false;  // GL_MESA_pack_invert: glReadPixels hands rows back from the top
  // The read-ahead's two pixel-buffer objects (made at the first startRead), which frames go into
  // in turn, and how many frames they hold that are not collected yet.
  const bool readAhead_;
  GLuint packBuffers_[2] = {0, 0};
  int nextBuffer_ = 0, pending_ = 0;

  void makeCurrent() override { context_->makeCurrent(); }
  void readFrame() override;
  void readAhead() override;
  void collectAhead() override;
  void makeFramebuffer();
  // The frame's rows from GL, strip by strip, to `out` (an image's pixels, or an offset into the
  // bound pixel-pack buffer), rows from the top where GL_MESA_pack_invert hands them so.
  void readRows(std::uint8_t* out);
  void flipRowsUnlessInverted();
};

EglContext::EglContext(bool gpu, bool readAhead, int width, int height)
    : GlContext(width, height, true), readAhead_(readAhead) {
  // The renderbuffer, and the strip glReadPixels reads through (render/frame_memory.hpp).
  reserveFrame(frameBytes(width, height) + std::min(frameBytes(width, height), kReadStripBytes));
  // Which display says nothing of memory (no hardware device, say): its errors go out as they are.
  const DisplayChoice choice = chooseDisplay(gpu);
  try {
    context_ = std::make_unique<OwnedContext>(initialize(choice.display));
    context_->makeCurrent();
  } catch (const RenderError& e) {
    throw RenderError(e.what() + reservationNote());
  }
  loadFunctions(eglGetProcAddress, "eglGetProcAddress", GlBackend::egl, choice.device);
  if (choice.mesaChose && isSoftwareRenderer(info().renderer) == gpu) {
    throw RenderError(
        gpu ? fmt::format("a GPU was asked for, but EGL's surfaceless platform chose the software rasteriser {}",
                          info().renderer)
            : fmt::format("EGL's surfaceless platform chose the GPU '{}', and EGL lists no software device; frames "
                          "are drawn on the CPU unless a GPU is asked for (LIBGL_ALWAYS_SOFTWARE=1 makes Mesa "
                          "choose llvmpipe)",
                          info().renderer));
  }
  GLint maxRenderbuffer = 0;
  gl().glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxRenderbuffer);
  checkGl(gl(), "glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE)");
  const GlSizeLimit limits[] = {{"GL_MAX_RENDERBUFFER_SIZE", maxRenderbuffer, maxRenderbuffer}, viewportLimit()};
  checkFrameSize(limits);
  releaseReservation();
  makeFramebuffer();
  packInvert_ = hasExtension(glString(gl(), GL_EXTENSIONS).c_str(), "GL_MESA_pack_invert");
  if (packInvert_) gl().glPixelStorei(GL_PACK_INVERT_MESA, GL_TRUE);
  checkGl(gl(), "glPixelStorei(GL_PACK_INVERT_MESA)");
}

// The frame's colour buffer: an RGBA8 renderbuffer of the frame's size, as OSMesa's buffer (no
// depth, stencil or multisampling: render/renderer.hpp), bound for the context's life.
void EglContext::makeFramebuffer() {
  const GlFunctions& g = gl();
  GLuint colour = 0, framebuffer = 0;  // freed with the context
  g.glGenRenderbuffers(1, &colour);
  g.glBindRenderbuffer(GL_RENDERBUFFER, colour);
  g.glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width_, height_);
  g.glGenFramebuffers(1, &framebuffer);
  g.glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  g.glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour);
  const std::string what = fmt::format("a {}x{} RGBA8 framebuffer", width_, height_);
  checkGl(g, what.c_str());
  // Mesa reports a renderbuffer it could not allocate as an incomplete attachment, not as
  // GL_OUT_OF_MEMORY.
  const GLenum status = g.glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status == GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT) {
    throw OutOfMemory(fmt::format("{} could not be allocated ({} MiB; GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT)", what,
                                  frameBytes(width_, height_) >> 20));
  }
  if (status != GL_FRAMEBUFFER_COMPLETE) throw RenderError(fmt::format("{} is incomplete: 0x{:04x}", what, status));
}

void EglContext::readRows(std::uint8_t* out) {
  // The picture's top row is GL window row height − 1 (flipsY); image rows go from the top. Rows
  // of 4-byte pixels need no packing beyond GL's default alignment of 4. Mesa reads through
  // scratch memory the size of what is asked for, so a large frame is read in strips of rows
  // (render/frame_memory.hpp); a 1280×720 frame is one.
  const std::size_t stride = image_.stride();
  const int stripRows = int(std::max<std::size_t>(1, kReadStripBytes / stride));
  for (int y = 0; y < height_; y += stripRows) {
    const int rows = std::min(stripRows, height_ - y);
    // With GL_MESA_pack_invert GL rows y … y + rows − 1 come top first: image rows from
    // height − y − rows. Without it they come as stored, to be swapped after.
    const int imageRow = packInvert_ ? height_ - y - rows : y;
    const std::size_t offset = std::size_t(imageRow) * stride;
    void* target = out != nullptr ? static_cast<void*>(out + offset) : reinterpret_cast<void*>(offset);
    gl().glReadPixels(0, y, width_, rows, GL_RGBA, GL_UNSIGNED_BYTE, target);
    checkGl(gl(), "glReadPixels");
  }
}

void EglContext::flipRowsUnlessInverted() {
  if (packInvert_) return;
  // A driver without GL_MESA_pack_invert (a GPU's): swap the rows here.
  for (int top = 0, bottom = image_.height - 1; top < bottom; ++top, --bottom) {
    std::swap_ranges(image_.pixel(0, top), image_.pixel(0, top) + image_.stride(), image_.pixel(0, bottom));
  }
}

void EglContext::readFrame() {
  // glReadPixels into client memory waits for the drawing to finish.
  readRows(image_.pixel(0, 0));
  flipRowsUnlessInverted();
}

void EglContext::readAhead() {
  if (pending_ == 2) throw std::logic_error("EglContext: a third frame read ahead before the first was collected");
  const GlFunctions& g = gl();
  const GLsizeiptr bytes = GLsizeiptr(frameBytes(width_, height_));
  if (packBuffers_[0] == 0) {
    // The memory checked first, as the frame's own (render/frame_memory.hpp): a failure is a message.
    MemoryReservation room(2 * std::size_t(bytes), fmt::format("two {}x{} frames read back ahead", width_, height_));
    room = {};
    g.glGenBuffers(2, packBuffers_);
    for (GLuint buffer : packBuffers_) {
      g.glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer);
      g.glBufferData(GL_PIXEL_PACK_BUFFER, bytes, nullptr, GL_STREAM_READ);
    }
    checkGl(g, fmt::format("two {} MiB pixel-pack buffers for reading frames back", bytes >> 20).c_str());
  }
  // With a pixel-pack buffer bound, glReadPixels takes an offset into it and returns once the copy
  // is queued: GL makes it while the next frame is drawn.
  g.glBindBuffer(GL_PIXEL_PACK_BUFFER, packBuffers_[nextBuffer_]);
  readRows(nullptr);
  g.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  nextBuffer_ = 1 - nextBuffer_;
  ++pending_;
}

void EglContext::collectAhead() {
  if (pending_ == 0) throw std::logic_error("EglContext: a frame collected that was not read");
  const GlFunctions& g = gl();
  const int oldest = pending_ == 2 ? nextBuffer_ : 1 - nextBuffer_;
  const std::size_t bytes = frameBytes(width_, height_);
  g.glBindBuffer(GL_PIXEL_PACK_BUFFER, packBuffers_[oldest]);
  // Mapping waits for that frame's copy, not for the frame drawn since.
  const void* pixels = g.glMapBufferRange(GL_PIXEL_PACK_BUFFER, 0, GLsizeiptr(bytes), GL_MAP_READ_BIT);
  if (pixels == nullptr) {
    g.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    checkGl(g, "glMapBufferRange(GL_PIXEL_PACK_BUFFER)");
    throw RenderError("glMapBufferRange(GL_PIXEL_PACK_BUFFER) returned no memory");
  }
  std::memcpy(image_.pixel(0, 0), pixels, bytes);
  g.glUnmapBuffer(GL_PIXEL_PACK_BUFFER);
  g.glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  checkGl(g, "reading a frame back from its pixel-pack buffer");
  --pending_;
  flipRowsUnlessInverted();
}

}  // namespace

std::unique_ptr<GlContext> makeEglContext(bool gpu, GlRequest::ReadBack readBack, int width, int height) {
  // automatic: ahead on a GPU only (GlRequest::readBack says why).
  const bool ahead = readBack == GlRequest::ReadBack::ahead || (readBack == GlRequest::ReadBack::automatic && gpu);
  return std::make_unique<EglContext>(gpu, ahead, width, height);
}

}  // namespace particles::render
