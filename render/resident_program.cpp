#include "render/resident_program.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "render/errors.hpp"
#include "render/gl_functions.hpp"
#include "render/shader_program.hpp"
#include "render/shape_mesh.hpp"

namespace particles::render {

namespace {

// The vertex shaders' shared part. Y_SIGN, FRINGE and the section (SPRINGS or PARTICLES) are
// defined before this text. Each instance is one shape of four corners, drawn as the triangles
// (0, 1, 2) and (0, 2, 3), as ShapeMesh::convex and ShapeMesh::annulus emit them.
constexpr const char* kResidentCommon = R"(
uniform vec2 imageSize;
uniform samplerBuffer positions;  // particles, in pixels (x right, y = image row)
in float corner;                  // 0 … 3: which of the instance's four corners
flat out vec4 vColor;
out vec4 vShape;
flat out float vKind;


// Corner i of the rectangle centre ± along · u ± across · v (|u| = |v| = 1, v = u turned a
// quarter), corners in the order (−u, +v), (+u, +v), (+u, −v), (−u, −v), grown by FRINGE on every
// edge, and the distances from it to the four edges (positive inside): what render/shape_mesh.cpp's
// convexEdges and ShapeMesh::convex give a rectangle whose edges are all smoothed, in closed form
// (the vertex shader runs for each of an instance's four corners: on llvmpipe, on one thread).
void grownCorner(vec2 centre, vec2 u, vec2 v, float along, float across, int i, out vec2 q, out vec4 shape) {
  float su = (i == 0 || i == 3) ? -1.0 : 1.0, sv = i < 2 ? 1.0 : -1.0;
  float grownAlong = su * (along + FRINGE), grownAcross = sv * (across + FRINGE);
  q = centre + grownAlong * u + grownAcross * v;
  // To the edges at +v, +u, −v and −u: −FRINGE on the corner's own sides, the rectangle's width
  // or length plus FRINGE to the opposite ones, interpolated in between.
  shape = vec4(across - grownAcross, along - grownAlong, across + grownAcross, along + grownAlong);
}

void place(vec2 q, bool drawn) {
  vec2 ndc = 2.0 * q / imageSize - 1.0;
  // A shape not drawn: all its corners at one point outside the view, nothing rasterised.
  gl_Position = drawn ? vec4(ndc.x, Y_SIGN * ndc.y, 0.0, 1.0) : vec4(2.0, 2.0, 0.0, 1.0);
}
)";

// Springs: instance i is spring i; ShapeSink::line's rectangle around the segment between its
// ends' positions, its width the spring's, no caps; its colour the look's (ownColors) or its
// strain's.
constexpr const char* kSpringVertexShader = R"(
uniform usamplerBuffer ends;  // two particle indices per spring
uniform samplerBuffer rest;   // rest lengths, world units
uniform usamplerBuffer springColors;  // RGBA 0 … 255, straight alpha, with ownColors
uniform bool ownColors;
uniform float halfWidth;      // pixels
uniform float pixelsPerUnit;
uniform float strainForFull;
uniform vec3 restColor, compressedColor, stretchedColor;  // 0 … 255
void main() {
  uvec2 e = texelFetch(ends, gl_InstanceID).xy;
  vec2 a = texelFetch(positions, int(e.x)).xy, b = texelFetch(positions, int(e.y)).xy;
  float len = length(b - a);
  vec2 q = vec2(0.0);
  vec4 shape = vec4(0.0);
  bool drawn = len > 1e-4;  // as ShapeSink::line: a degenerate segment is not drawn
  if (drawn) {
    vec2 u = (b - a) / len;
    grownCorner(0.5 * (a + b), u, vec2(-u.y, u.x), 0.5 * len, halfWidth, int(corner), q, shape);
  }
  place(q, drawn);
  // springColor (render/theme.cpp): the strain |l| / rest − 1, towards the full colour, each
  // channel rounded to its nearest level as mix does.
  float r = texelFetch(rest, gl_InstanceID).x;
  float strain = r > 0.0 ? len / pixelsPerUnit / r - 1.0 : 0.0;
  float t = clamp(strain / strainForFull, -1.0, 1.0);
  vec3 target = t < 0.0 ? compressedColor : stretchedColor;
  vColor = ownColors ? vec4(texelFetch(springColors, gl_InstanceID)) / 255.0
                     : vec4(floor(restColor + (target - restColor) * abs(t) + 0.5) / 255.0, 1.0);
  vShape = shape;
  vKind = 0.0;
}
)";

// Particles: instance i is particle i, a disc (ShapeMesh::annulus's one square for a small disc,
// which serves any disc: coverage comes from the distance to the centre) or, fixed, a square of
// side 1.8 radius (render/frame_mesh.cpp); its colour and radius the look's where it gives them.
constexpr const char* kParticleVertexShader = R"(
uniform usamplerBuffer fixedFlags;  // 1: a fixed particle
uniform usamplerBuffer particleColors;  // RGBA 0 … 255, straight alpha, with ownColors
uniform samplerBuffer particleRadii;    // pixels, with ownRadii
uniform bool ownColors, ownRadii;
uniform float themeRadius;              // pixels
uniform vec3 particleColor, fixedColor;  // 0 … 255
void main() {
  vec2 p = texelFetch(positions, gl_InstanceID).xy;
  float radius = ownRadii ? texelFetch(particleRadii, gl_InstanceID).x : themeRadius;
  int k = int(corner);
  vec2 q;
  vec4 shape;
  bool fixedParticle = texelFetch(fixedFlags, gl_InstanceID).x != 0u;
  if (fixedParticle) {
    grownCorner(p, vec2(1.0, 0.0), vec2(0.0, 1.0), 0.9 * radius, 0.9 * radius, k, q, shape);
  } else {
    float r = radius + FRINGE;
    vec2 o = vec2[4](vec2(-r, r), vec2(r, r), vec2(r, -r), vec2(-r, -r))[k];
    q = p + o;
    shape = vec4(o, radius, 0.0);
  }
  place(q, 0.9 * radius > 1e-4 || !fixedParticle);
  vColor = ownColors ? vec4(texelFetch(particleColors, gl_InstanceID)) / 255.0
                     : vec4((fixedParticle ? fixedColor : particleColor) / 255.0, 1.0);
  vShape = shape;
  vKind = fixedParticle ? 0.0 : 1.0;
}
)";

constexpr GLenum kResidentFormats[] = {GL_RG32F, GL_R8UI, GL_RG32UI, GL_R32F, GL_RGBA8UI, GL_R32F, GL_RGBA8UI};
static_assert(sizeof(Rgba) == 4, "a look's colours go to GL as they are, 4 bytes each");
// Each instance's four corners, numbered (the vertex shader's `corner`).
constexpr float kInstanceCorners[4] = {0, 1, 2, 3};
// Each instance's two triangles, (0, 1, 2) and (0, 2, 3) as ShapeMesh emits a quad's: indexed, so
// that the four corners are shaded once each (GL's vertex cache) rather than six times.
constexpr GLubyte kInstanceTriangles[6] = {0, 1, 2, 0, 2, 3};

void setColor(const GlFunctions& gl, unsigned program, const char* name, Rgb c) {
  gl.glUniform3f(gl.glGetUniformLocation(program, name), float(c.r), float(c.g), float(c.b));
}

}  // namespace

ResidentProgram::ResidentProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY) : gl_(gl) {
  const std::string header = std::string("#version 140\n#define Y_SIGN ") + (flipY ? "-1.0" : "1.0") +
                             "\n#define FRINGE " + std::to_string(kFringePx) + "\n" + kResidentCommon;
  const auto link = [&](const char* vertexShader, CoverageKinds kinds) {
    Program p;
    p.name = linkProgram(gl, header + vertexShader, coverageFragmentShader(samples, flipY, kinds));
    p.corner = gl.glGetAttribLocation(p.name, "corner");
    return p;
  };
  springs_ = link(kSpringVertexShader, CoverageKinds::edgesOnly);
  particles_ = link(kParticleVertexShader, CoverageKinds::edgesAndDiscs);
  freeParticles_ = link(kParticleVertexShader, CoverageKinds::discsOnly);
  gl.glGenBuffers(kBufferCount, buffers_);
  gl.glGenTextures(kBufferCount, textures_);
  for (unsigned program : {springs_.name, particles_.name, freeParticles_.name}) {
    gl.glUseProgram(program);
    gl.glUniform2f(gl.glGetUniformLocation(program, "imageSize"), float(width), float(height));
    gl.glUniform1i(gl.glGetUniformLocation(program, "positions"), kPositions);
  }
  gl.glUseProgram(springs_.name);
  gl.glUniform1i(gl.glGetUniformLocation(springs_.name, "ends"), kEnds);
  gl.glUniform1i(gl.glGetUniformLocation(springs_.name, "rest"), kRest);
  gl.glUniform1i(gl.glGetUniformLocation(springs_.name, "springColors"), kSpringColors);
  for (unsigned program : {particles_.name, freeParticles_.name}) {
    gl.glUseProgram(program);
    gl.glUniform1i(gl.glGetUniformLocation(program, "fixedFlags"), kFixed);
    gl.glUniform1i(gl.glGetUniformLocation(program, "particleColors"), kParticleColors);
    gl.glUniform1i(gl.glGetUniformLocation(program, "particleRadii"), kParticleRadii);
  }
  GLint most = 0;
  gl.glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &most);
  maxTexels_ = most;
  // Every buffer holds a texel from the start: GL wants no texture buffer without a store.
  const std::uint32_t zero[2] = {0, 0};
  for (int b = 0; b < kBufferCount; ++b) fill(Buffer(b), zero, sizeof zero);
  checkGl(gl, "resident program setup");
}

bool ResidentProgram::fits(size_t particles, size_t springs) const {
  return (long long)particles <= maxTexels_ && (long long)springs <= maxTexels_;
}

void ResidentProgram::fill(Buffer b, const void* data, size_t bytes) {
  const GlFunctions& gl = gl_;
  gl.glActiveTexture(GL_TEXTURE0 + b);
  gl.glBindBuffer(GL_TEXTURE_BUFFER, buffers_[b]);
  if (bytes > capacity_[b]) {
    // Grown by half again, as the tile path's buffers (render/tile_program.cpp says why).
    capacity_[b] = capacity_[b] == 0 ? bytes : bytes + bytes / 2;
    gl.glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(capacity_[b]), nullptr, GL_DYNAMIC_DRAW);
    gl.glBindTexture(GL_TEXTURE_BUFFER, textures_[b]);
    gl.glTexBuffer(GL_TEXTURE_BUFFER, kResidentFormats[b], buffers_[b]);
  }
  if (bytes > 0) gl.glBufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(bytes), data);
  gl.glBindBuffer(GL_TEXTURE_BUFFER, 0);
  gl.glActiveTexture(GL_TEXTURE0);
}

void ResidentProgram::upload(std::span<const float> pixels, std::span<const char> fixed,
                             const std::shared_ptr<const Drawing::SpringTopology>& springs) {
  particleCount_ = pixels.size() / 2;
  fill(kPositions, pixels.data(), pixels.size_bytes());
  // The flags, one byte a particle as GL takes them: sent again only when they change (a scene's
  // pins rarely do).
  flags_.assign(particleCount_, 0);
  for (size_t i = 0; i < std::min(fixed.size(), particleCount_); ++i) flags_[i] = fixed[i] != 0 ? 1 : 0;
  if (flags_ != fixed_) {
    fixed_.swap(flags_);
    fill(kFixed, fixed_.data(), fixed_.size());
    anyFixed_ = std::find(fixed_.begin(), fixed_.end(), 1) != fixed_.end();
  }
  if (springs != topology_) {
    topology_ = springs;
    springCount_ = springs ? springs->rest.size() : 0;
    if (springs) {
      if (springs->ends.size() != 2 * springCount_) throw std::logic_error("a spring topology without two ends per spring");
      const std::vector<float> rest(springs->rest.begin(), springs->rest.end());  // as GL takes them
      fill(kEnds, springs->ends.data(), springs->ends.size() * sizeof(std::uint32_t));
      fill(kRest, rest.data(), rest.size() * sizeof(float));
      ++topologyUploads_;
    }
    particlesNeeded_ = springs && !springs->ends.empty()
                           ? size_t(*std::max_element(springs->ends.begin(), springs->ends.end())) + 1
                           : 0;
  }
  // A spring whose end is not one of the frame's particles would be drawn from no position.
  if (particlesNeeded_ > particleCount_) {
    throw std::invalid_argument("a spring of the drawing's topology ends at particle " +
                                std::to_string(particlesNeeded_ - 1) + ", and the drawing has " +
                                std::to_string(particleCount_) + " particles");
  }
  checkGl(gl_, "sending the resident path's buffers");
}

void ResidentProgram::uploadLook(std::span<const Rgba> particleColors, std::span<const float> particleRadiiPx,
                                 std::span<const Rgba> springColors) {
  const auto check = [](size_t given, size_t wanted, const char* what) {
    if (given != 0 && given != wanted) {
      throw std::invalid_argument(std::string("the resident path was given ") + std::to_string(given) + " " + what +
                                  " for " + std::to_string(wanted));
    }
    return given != 0;
  };
  ownParticleColors_ = check(particleColors.size(), particleCount_, "particle colours");
  ownParticleRadii_ = check(particleRadiiPx.size(), particleCount_, "particle radii");
  ownSpringColors_ = check(springColors.size(), springCount_, "spring colours");
  if (ownParticleColors_) fill(kParticleColors, particleColors.data(), particleColors.size_bytes());
  if (ownParticleRadii_) fill(kParticleRadii, particleRadiiPx.data(), particleRadiiPx.size_bytes());
  if (ownSpringColors_) fill(kSpringColors, springColors.data(), springColors.size_bytes());
  checkGl(gl_, "sending the resident path's look");
}

void ResidentProgram::drawInstances(const Program& program, size_t instances) const {
  const int cornerAttr = program.corner;
  if (instances == 0 || cornerAttr < 0) return;
  const GlFunctions& gl = gl_;
  for (int b = 0; b < kBufferCount; ++b) {
    gl.glActiveTexture(GL_TEXTURE0 + b);
    gl.glBindTexture(GL_TEXTURE_BUFFER, textures_[b]);
  }
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glEnableVertexAttribArray(GLuint(cornerAttr));
  gl.glVertexAttribPointer(GLuint(cornerAttr), 1, GL_FLOAT, GL_FALSE, 0, kInstanceCorners);
  gl.glDrawElementsInstanced(GL_TRIANGLES, 6, GL_UNSIGNED_BYTE, kInstanceTriangles, GLsizei(instances));
  gl.glDisableVertexAttribArray(GLuint(cornerAttr));
}

void ResidentProgram::drawSprings(const ResidentLook& look) const {
  const GlFunctions& gl = gl_;
  const unsigned program = springs_.name;
  gl.glUseProgram(program);
  gl.glUniform1f(gl.glGetUniformLocation(program, "halfWidth"), 0.5f * look.springWidthPx);
  gl.glUniform1f(gl.glGetUniformLocation(program, "pixelsPerUnit"), float(look.pixelsPerUnit));
  gl.glUniform1f(gl.glGetUniformLocation(program, "strainForFull"), float(look.strainForFullColor));
  setColor(gl, program, "restColor", look.colors.springRest);
  setColor(gl, program, "compressedColor", look.colors.springCompressed);
  setColor(gl, program, "stretchedColor", look.colors.springStretched);
  gl.glUniform1i(gl.glGetUniformLocation(program, "ownColors"), ownSpringColors_ ? 1 : 0);
  drawInstances(springs_, springCount_);
}

void ResidentProgram::drawParticles(const ResidentLook& look) const {
  const GlFunctions& gl = gl_;
  const Program& particles = anyFixed_ ? particles_ : freeParticles_;
  gl.glUseProgram(particles.name);
  gl.glUniform1f(gl.glGetUniformLocation(particles.name, "themeRadius"), look.particleRadiusPx);
  setColor(gl, particles.name, "particleColor", look.colors.particle);
  setColor(gl, particles.name, "fixedColor", look.colors.fixedParticle);
  gl.glUniform1i(gl.glGetUniformLocation(particles.name, "ownColors"), ownParticleColors_ ? 1 : 0);
  gl.glUniform1i(gl.glGetUniformLocation(particles.name, "ownRadii"), ownParticleRadii_ ? 1 : 0);
  drawInstances(particles, particleCount_);
}

}  // namespace particles::render
