#include "render/gl_functions.hpp"

#include <fmt/format.h>

#include "render/errors.hpp"

namespace particles::render {

namespace {

std::string glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return fmt::format("0x{:04x}", e);
  }
}

}  // namespace

GlFunctions loadGlFunctions(GlProcLookup lookup, const char* lookupName) {
  GlFunctions gl;
#define PARTICLES_GL_LOAD(name)                                                     \
  gl.name = reinterpret_cast<decltype(gl.name)>(lookup(#name));                     \
  if (!gl.name) {                                                                   \
    throw RenderError(                                                              \
        fmt::format("{}(\"{}\") found no such function: the OpenGL library is too " \
                    "old for the renderer (it needs OpenGL 3.1)",                   \
                    lookupName, #name));                                            \
  }
  PARTICLES_GL_FUNCTIONS(PARTICLES_GL_LOAD)
#undef PARTICLES_GL_LOAD
  return gl;
}

void checkGl(const GlFunctions& gl, const char* what) {
  const GLenum e = gl.glGetError();
  if (e != GL_NO_ERROR) throw RenderError(fmt::format("{}: OpenGL error {}", what, glErrorName(e)));
}

std::string glString(const GlFunctions& gl, GLenum name) {
  const GLubyte* text = gl.glGetString(name);
  return text ? reinterpret_cast<const char*>(text) : "";
}

}  // namespace particles::render
