#pragma once
// Internal to render/: the OpenGL entry points the renderer calls, looked up through the backend
// that made the context (OSMesaGetProcAddress, eglGetProcAddress) and called through this table.
//
// Why not call gl* directly: libOSMesa exports GL functions of its own, and GLVND's libOpenGL
// exports others; a program linking both gets one set, bound to one library, whichever the linker
// finds first. A table per context calls each backend's own functions, and the EGL-only build
// links no GL library at all (a direct call there fails to link, which is how it is caught).
// libepoxy would do the lookup for EGL but does not know OSMesa contexts; the list is short.

#define GL_GLEXT_PROTOTYPES 1  // the prototypes give each entry point's type below, nothing more
#include <GL/gl.h>
#include <GL/glext.h>

#include <string>

namespace particles::render {

// Every GL function the renderer calls, by name. A new call is one more name here.
// clang-format off
#define PARTICLES_GL_FUNCTIONS(X)                                                                       \
  /* state, frame */ X(glGetError) X(glGetString) X(glFinish) X(glViewport) X(glEnable) X(glDisable)    \
  X(glBlendFuncSeparate) X(glClearColor) X(glClear) X(glPixelStorei) X(glReadPixels)                    \
  /* shaders */ X(glCreateShader) X(glShaderSource) X(glCompileShader) X(glGetShaderiv)                 \
  X(glGetShaderInfoLog) X(glDeleteShader) X(glCreateProgram) X(glAttachShader) X(glLinkProgram)         \
  X(glGetProgramiv) X(glGetProgramInfoLog) X(glUseProgram) X(glGetAttribLocation)                       \
  X(glGetUniformLocation) X(glUniform2f)                                                                \
  /* drawing */ X(glEnableVertexAttribArray) X(glDisableVertexAttribArray) X(glVertexAttribPointer)     \
  X(glDrawArrays) X(glDrawElementsInstanced)                                                            \
  /* the tile path's texture buffers */ X(glGenBuffers) X(glBindBuffer) X(glBufferData) X(glBufferSubData) \
  X(glGenTextures) X(glBindTexture) X(glTexBuffer) X(glActiveTexture) X(glUniform1i) X(glUniform1f) X(glUniform3f)        \
  X(glGetIntegerv)                                                                                      \
  /* the read-back's pixel-pack buffers */ X(glMapBufferRange) X(glUnmapBuffer)                          \
  /* the EGL backend's framebuffer */ X(glGenRenderbuffers) X(glBindRenderbuffer)                       \
  X(glRenderbufferStorage) X(glGenFramebuffers) X(glBindFramebuffer) X(glFramebufferRenderbuffer)       \
  X(glCheckFramebufferStatus)
// clang-format on

struct GlFunctions {
#define PARTICLES_GL_MEMBER(name) decltype(&::name) name = nullptr;
  PARTICLES_GL_FUNCTIONS(PARTICLES_GL_MEMBER)
#undef PARTICLES_GL_MEMBER
};

// What OSMesaGetProcAddress and eglGetProcAddress both are.
using GlProcLookup = void (*(*)(const char* name))();

// Looks every entry point up with `lookup` (named `lookupName` in errors) in the current context.
// Throws RenderError naming the first one it does not find.
GlFunctions loadGlFunctions(GlProcLookup lookup, const char* lookupName);

// Throws RenderError("WHAT: OpenGL error NAME") if GL has recorded an error.
void checkGl(const GlFunctions& gl, const char* what);

// GL_RENDERER, GL_VERSION and the like of the current context; "" when GL has none.
std::string glString(const GlFunctions& gl, GLenum name);

}  // namespace particles::render
