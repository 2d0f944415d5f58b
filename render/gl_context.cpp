#include "render/gl_context.hpp"

#define GL_GLEXT_PROTOTYPES 1
#include <GL/osmesa.h>
// osmesa.h brings in GL/gl.h; libOSMesa exports the GL 3 entry points (framebuffer objects) too.
#include <GL/glext.h>

#include <cstdio>
#include <string>

#include "render/errors.hpp"

namespace particles::render {

namespace {

std::string hex(unsigned v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%04x", v);
  return buf;
}

std::string glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return hex(e);
  }
}

}  // namespace

void checkGl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) throw RenderError(std::string(what) + ": OpenGL error " + glErrorName(e));
}

// Destroying the context frees the shader program with it.
void GlContext::ContextDeleter::operator()(osmesa_context* context) const {
  OSMesaDestroyContext(context);
}

GlContext::GlContext(int width, int height) : image_(width, height) {
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
        "OpenGL context (is libOSMesa's software rasteriser, llvmpipe or softpipe, installed?)");
  }
  makeCurrent();
  // Image row 0 must be the top of the picture: with OSMESA_Y_UP = 1 (the default) memory row 0 is
  // GL window row 0, and the frame's mesh (render/frame_mesh.hpp) puts the top of the view there.
  OSMesaPixelStore(OSMESA_Y_UP, 1);
}

void GlContext::makeCurrent() {
  if (!OSMesaMakeCurrent(context_.get(), image_.rgba.data(), GL_UNSIGNED_BYTE, image_.width, image_.height)) {
    throw RenderError("OSMesaMakeCurrent(" + std::to_string(image_.width) + "x" + std::to_string(image_.height) +
                      ", GL_UNSIGNED_BYTE) failed");
  }
}

void GlContext::beginFrame(Rgb bg) {
  makeCurrent();
  glViewport(0, 0, image_.width, image_.height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_DITHER);
  // Coverage as alpha over what is drawn (render/shader_program.hpp); the destination keeps alpha 1.
  glEnable(GL_BLEND);
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(float(bg.r) / 255.0f, float(bg.g) / 255.0f, float(bg.b) / 255.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
}

const Image& GlContext::finishFrame() {
  checkGl("drawing the frame");
  glFinish();
  checkGl("glFinish");
  return image_;
}

}  // namespace particles::render
