#pragma once
// Internal to render/: the coverage shader. Each primitive carries its true boundary
// (render/shape_mesh.hpp), the fragment shader tests the pixel's samples, at the standard
// positions (samplePattern), against it, and the share covered becomes the fragment's alpha,
// blended over what is already drawn (render/gl_context.hpp). For one edge over a background this
// is exactly what a multisampled framebuffer resolves to (render/renderer.hpp says why we do not
// use one).

#include <string>
#include <vector>

#include "core/state.hpp"
#include "render/shape_mesh.hpp"

namespace particles::render {

struct GlFunctions;  // render/gl_functions.hpp

// The sample positions for each of kSampleCounts (render/render_options.hpp): offsets from the
// pixel centre in pixels, x right, y down (Direct3D's and Vulkan's standard patterns; 1 is the
// centre itself). Throws std::invalid_argument for another count.
const std::vector<Vec2>& samplePattern(int samples);

// `#define SAMPLE_COUNT n` and `#define SAMPLES vec2(…), …`: the pattern of `samples` for a shader.
std::string samplePatternGlsl(int samples);

// The coverage fragment shader's whole text (GLSL 1.30) for `samples` per pixel: it takes the
// primitive's colour (vColor), boundary (vShape, render/shape_mesh.hpp's ShapeVertex::shape) and
// kind (flat vKind) from the vertex shader; `flipY` as ShaderProgram's. The resident path's vertex
// shaders (render/resident_program.hpp) feed it the same, so every triangle-drawing path blends
// the same coverage. `kinds` says which boundaries its primitives can have: a program that draws
// only edge-bounded shapes (the resident path's springs) leaves the disc's test out, and one that
// draws only discs (its particles, in a frame with none fixed) the edges' test: the same coverage
// for fewer operations per sample.
enum class CoverageKinds { edgesAndDiscs, edgesOnly, discsOnly };
std::string coverageFragmentShader(int samples, bool flipY, CoverageKinds kinds = CoverageKinds::edgesAndDiscs);

// Compiles and links a program of the two sources in the current context. Throws RenderError with
// the compiler's or the linker's log.
unsigned linkProgram(const GlFunctions& gl, const std::string& vertexSource, const std::string& fragmentSource);

class ShaderProgram {
 public:
  // Compiles and links the shader for `samples` per pixel and images of width × height pixels in
  // the current GL context, whose functions `gl` are (they outlive the program), and makes it
  // current there. Image row y is GL window row y, or height − y with `flipY` (the context's
  // GlContext::flipsY). Throws RenderError with the compiler's or the linker's log,
  // std::invalid_argument for a sample count without a pattern.
  ShaderProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY);
  // No destructor: the program belongs to its context and is freed with it (deleting it here
  // would need that context current, and another renderer's may be).
  ShaderProgram(const ShaderProgram&) = delete;
  ShaderProgram& operator=(const ShaderProgram&) = delete;

  // Draws the mesh's triangles in order, in the current context (nothing for an empty mesh); or
  // only its vertices [first, end).
  void draw(const ShapeMesh& mesh) const { draw(mesh, 0, mesh.vertices().size()); }
  void draw(const ShapeMesh& mesh, size_t first, size_t end) const;

 private:
  const GlFunctions& gl_;
  unsigned program_ = 0;  // GLuint
  // GLint locations; an attribute the compiler dropped has location −1 and is skipped.
  int positionAttr_ = -1, colorAttr_ = -1, shapeAttr_ = -1, kindAttr_ = -1;
};

}  // namespace particles::render
