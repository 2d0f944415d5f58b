#include "render/shader_program.hpp"

#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "render/errors.hpp"
#include "render/gl_functions.hpp"

namespace particles::render {

static_assert(std::is_same_v<GLuint, unsigned> && std::is_same_v<GLint, int>, "ShaderProgram holds GL names as ints");

namespace {

// Compiled with Y_SIGN defined before this text: 1.0 puts image row y at GL window row y, −1.0 at
// window row height − y (ShaderProgram's flipY, render/gl_context.hpp).
constexpr const char* kVertexShader = R"(
uniform vec2 imageSize;
in vec2 position;   // pixels, x right, y = image row
in vec4 color;
in vec4 shape;
in float kind;
flat out vec4 vColor;  // a shape's one colour (its every vertex has it): not interpolated per pixel
out vec4 vShape;
flat out float vKind;
void main() {
  vec2 ndc = 2.0 * position / imageSize - 1.0;
  gl_Position = vec4(ndc.x, Y_SIGN * ndc.y, 0.0, 1.0);
  vColor = color;
  vShape = shape;
  vKind = kind;
}
)";

// Compiled once per sample count (SAMPLE_COUNT, SAMPLES and Y_SIGN are defined before this text) so
// the loop unrolls and llvmpipe's vectorised code has no branches: both shape kinds are evaluated
// and one is selected, unless the program draws one kind only (EDGES_ONLY, DISCS_ONLY: the
// compiler drops the other's arithmetic). dFdy is along GL's window y; times Y_SIGN, along image
// rows (y down).
constexpr const char* kFragmentShader = R"(
flat in vec4 vColor;
in vec4 vShape;
flat in float vKind;
void main() {
  const vec2 samples[SAMPLE_COUNT] = vec2[SAMPLE_COUNT](SAMPLES);
  vec4 ddx = dFdx(vShape), ddy = Y_SIGN * dFdy(vShape);  // exact: edge distances are affine in position
  float rOut2 = vShape.z * vShape.z, rIn2 = vShape.w * vShape.w;
  float covered = 0.0;
  for (int i = 0; i < SAMPLE_COUNT; ++i) {
    vec2 o = samples[i];
    vec2 q = vShape.xy + o;
    float r2 = dot(q, q);
    vec4 d = vShape + ddx * o.x + ddy * o.y;
    bool inEdges = min(min(d.x, d.y), min(d.z, d.w)) >= 0.0;
    bool inCircle = r2 <= rOut2 && r2 >= rIn2;
#if defined(EDGES_ONLY)
    covered += inEdges ? 1.0 : 0.0;
#elif defined(DISCS_ONLY)
    covered += inCircle ? 1.0 : 0.0;
#else
    covered += (vKind > 0.5 ? inCircle : inEdges) ? 1.0 : 0.0;
#endif
  }
  if (covered == 0.0) discard;
  gl_FragColor = vec4(vColor.rgb, vColor.a * covered / float(SAMPLE_COUNT));
}
)";

// The info log of a shader or program whose `status` (compile or link) is not GL_TRUE; nothing when
// it is. getStatus and getLog are the shader's or the program's pair of GL queries.
std::optional<std::string> failureLog(GLuint object, GLenum status, void (*getStatus)(GLuint, GLenum, GLint*),
                                      void (*getLog)(GLuint, GLsizei, GLsizei*, GLchar*)) {
  GLint ok = GL_FALSE;
  getStatus(object, status, &ok);
  if (ok == GL_TRUE) return std::nullopt;
  char log[2048] = {};
  getLog(object, sizeof log, nullptr, log);
  return log;
}

GLuint compileShader(const GlFunctions& gl, GLenum type, const char* source, const char* name) {
  const GLuint shader = gl.glCreateShader(type);
  gl.glShaderSource(shader, 1, &source, nullptr);
  gl.glCompileShader(shader);
  if (const auto log = failureLog(shader, GL_COMPILE_STATUS, gl.glGetShaderiv, gl.glGetShaderInfoLog)) {
    gl.glDeleteShader(shader);
    throw RenderError(std::string("compiling the ") + name + " shader failed: " + *log);
  }
  return shader;
}

}  // namespace

const std::vector<Vec2>& samplePattern(int samples) {
  // The standard sample positions of Direct3D and Vulkan, given in 1/16 pixel, y down.
  auto inPixels = [](std::vector<Vec2> sixteenths) {
    for (Vec2& o : sixteenths) o /= 16.0;
    return sixteenths;
  };
  static const std::vector<Vec2> p1 = {Vec2(0, 0)};
  static const std::vector<Vec2> p2 = inPixels({Vec2(4, 4), Vec2(-4, -4)});
  static const std::vector<Vec2> p4 = inPixels({Vec2(-2, -6), Vec2(6, -2), Vec2(-6, 2), Vec2(2, 6)});
  static const std::vector<Vec2> p8 = inPixels(
      {Vec2(1, -3), Vec2(-1, 3), Vec2(5, 1), Vec2(-3, -5), Vec2(-5, 5), Vec2(-7, -1), Vec2(3, 7), Vec2(7, -7)});
  static const std::vector<Vec2> p16 = inPixels(
      {Vec2(1, 1), Vec2(-1, -3), Vec2(-3, 2), Vec2(4, -1), Vec2(-5, -2), Vec2(2, 5), Vec2(5, 3), Vec2(3, -5),
       Vec2(-2, 6), Vec2(0, -7), Vec2(-4, -6), Vec2(-6, 4), Vec2(-8, 0), Vec2(7, -4), Vec2(6, 7), Vec2(-7, -8)});
  switch (samples) {
    case 1: return p1;
    case 2: return p2;
    case 4: return p4;
    case 8: return p8;
    case 16: return p16;
    default: throw std::invalid_argument("no sample pattern for " + std::to_string(samples) + " samples");
  }
}

std::string samplePatternGlsl(int samples) {
  const std::vector<Vec2>& pattern = samplePattern(samples);
  std::string text = "#define SAMPLE_COUNT " + std::to_string(pattern.size()) + "\n#define SAMPLES ";
  for (size_t i = 0; i < pattern.size(); ++i) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%svec2(%.6f, %.6f)", i ? ", " : "", pattern[i].x(), pattern[i].y());
    text += buf;
  }
  return text + "\n";
}

unsigned linkProgram(const GlFunctions& gl, const std::string& vertexSource, const std::string& fragmentSource) {
  const GLuint vs = compileShader(gl, GL_VERTEX_SHADER, vertexSource.c_str(), "vertex");
  GLuint fs = 0;
  try {
    fs = compileShader(gl, GL_FRAGMENT_SHADER, fragmentSource.c_str(), "fragment");
  } catch (...) {
    gl.glDeleteShader(vs);
    throw;
  }
  const GLuint program = gl.glCreateProgram();
  gl.glAttachShader(program, vs);
  gl.glAttachShader(program, fs);
  gl.glLinkProgram(program);
  gl.glDeleteShader(vs);  // freed with the program
  gl.glDeleteShader(fs);
  if (const auto log = failureLog(program, GL_LINK_STATUS, gl.glGetProgramiv, gl.glGetProgramInfoLog)) {
    throw RenderError(std::string("linking the shader program failed: ") + *log);
  }
  return program;
}

std::string coverageFragmentShader(int samples, bool flipY, CoverageKinds kinds) {
  return std::string("#version 130\n#define Y_SIGN ") + (flipY ? "-1.0" : "1.0") + "\n" +
         (kinds == CoverageKinds::edgesOnly   ? "#define EDGES_ONLY\n"
          : kinds == CoverageKinds::discsOnly ? "#define DISCS_ONLY\n"
                                              : "") + samplePatternGlsl(samples) + kFragmentShader;
}

ShaderProgram::ShaderProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY) : gl_(gl) {
  const std::string ySign = std::string("#version 130\n#define Y_SIGN ") + (flipY ? "-1.0" : "1.0") + "\n";
  program_ = linkProgram(gl, ySign + kVertexShader, coverageFragmentShader(samples, flipY));
  positionAttr_ = gl.glGetAttribLocation(program_, "position");
  colorAttr_ = gl.glGetAttribLocation(program_, "color");
  shapeAttr_ = gl.glGetAttribLocation(program_, "shape");
  kindAttr_ = gl.glGetAttribLocation(program_, "kind");
  gl.glUseProgram(program_);
  gl.glUniform2f(gl.glGetUniformLocation(program_, "imageSize"), float(width), float(height));
  checkGl(gl, "shader program setup");
}

void ShaderProgram::draw(const ShapeMesh& mesh, size_t first, size_t end) const {
  if (first >= end) return;
  const ShapeVertex* v = mesh.vertices().data();
  const GLsizei stride = sizeof(ShapeVertex);
  gl_.glUseProgram(program_);
  const GLint attrs[] = {positionAttr_, colorAttr_, shapeAttr_, kindAttr_};
  for (GLint a : attrs) {
    if (a >= 0) gl_.glEnableVertexAttribArray(GLuint(a));
  }
  if (positionAttr_ >= 0) gl_.glVertexAttribPointer(GLuint(positionAttr_), 2, GL_FLOAT, GL_FALSE, stride, &v->x);
  if (colorAttr_ >= 0) gl_.glVertexAttribPointer(GLuint(colorAttr_), 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, v->rgba);
  if (shapeAttr_ >= 0) gl_.glVertexAttribPointer(GLuint(shapeAttr_), 4, GL_FLOAT, GL_FALSE, stride, v->shape);
  if (kindAttr_ >= 0) gl_.glVertexAttribPointer(GLuint(kindAttr_), 1, GL_FLOAT, GL_FALSE, stride, &v->kind);
  gl_.glDrawArrays(GL_TRIANGLES, GLint(first), GLsizei(end - first));
  for (GLint a : attrs) {
    if (a >= 0) gl_.glDisableVertexAttribArray(GLuint(a));
  }
}

}  // namespace particles::render
