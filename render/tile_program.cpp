#include "render/tile_program.hpp"

#include <string>

#include "render/errors.hpp"
#include "render/gl_functions.hpp"
#include "render/shader_program.hpp"

namespace particles::render {

namespace {

// FLIP_Y is defined before this text.
constexpr const char* kTileVertexShader = R"(
uniform vec2 imageSize;
in vec2 position;  // a corner of a run of tiles, in image pixels (x right, y down)
void main() {
  vec2 ndc = 2.0 * position / imageSize - 1.0;
  gl_Position = vec4(ndc.x, FLIP_Y ? -ndc.y : ndc.y, 0.0, 1.0);
}
)";

// SAMPLE_COUNT, SAMPLES (samplePatternGlsl), FLIP_Y, TILE and FAR are defined before this text.
// Records: render/tile_bins.hpp.
constexpr const char* kTileFragmentShader = R"(
uniform samplerBuffer shapes;
uniform usamplerBuffer tiles;
uniform usamplerBuffer items;
uniform int tilesPerRow;
uniform float imageHeight;
uniform vec3 background;  // 0 … 255
uniform float backgroundAlpha;  // 1 opaque, 0 transparent: then the colour stays premultiplied
out vec4 fragColor;

const vec2 samples[SAMPLE_COUNT] = vec2[SAMPLE_COUNT](SAMPLES);

// How many of the samples around pixel centre c (image pixels, y down) shape s covers: the test of
// the triangle path's fragment shader (render/shader_program.cpp), with the edge distances
// evaluated here instead of interpolated. No branches: llvmpipe runs both sides of one anyway.
// Also gives the shape's colour and alpha (0 … 255).
int coveredSamples(int s, vec2 c, out vec3 color, out float opacity) {
  vec4 t0 = texelFetch(shapes, 4 * s), t1 = texelFetch(shapes, 4 * s + 1);
  vec4 t2 = texelFetch(shapes, 4 * s + 2), t3 = texelFetch(shapes, 4 * s + 3);
  float b = floor(t3.x / 65536.0), g = floor((t3.x - 65536.0 * b) / 256.0);
  color = vec3(t3.x - 65536.0 * b - 256.0 * g, g, b);
  opacity = t3.z;
  bool annulus = t3.y == KIND_ANNULUS;
  // Convex: edge distances at the centre. An edge shared with another piece of the same shape
  // (not smoothed) is decided by the centre, as the rasteriser does for the triangle path's
  // unpushed edge, and not tested per sample.
  vec4 d = t2 + t0 * c.x + t1 * c.y;
  vec4 smoothed = vec4(notEqual(ivec4(int(t3.y)) & ivec4(1, 2, 4, 8), ivec4(0)));
  vec4 untested = (1.0 - smoothed) * FAR;
  bool centreInside = annulus || !any(lessThan(d + smoothed * FAR, vec4(0.0)));
  // Annulus: the offset from the centre, and the radii squared.
  vec2 q = c - t0.xy;
  float outer2 = t0.z * t0.z, inner2 = t0.w * t0.w;
  int n = 0;
  for (int i = 0; i < SAMPLE_COUNT; ++i) {
    vec2 o = samples[i];
    bool inEdges = all(greaterThanEqual(d + t0 * o.x + t1 * o.y + untested, vec4(0.0)));
    vec2 p = q + o;
    float r2 = dot(p, p);
    bool inRing = r2 <= outer2 && r2 >= inner2;
    n += (annulus ? inRing : inEdges) ? 1 : 0;
  }
  return centreInside ? n : 0;
}

void main() {
  vec2 c = vec2(gl_FragCoord.x, FLIP_Y ? imageHeight - gl_FragCoord.y : gl_FragCoord.y);
  ivec2 pixel = ivec2(c);
  uvec2 range = texelFetch(tiles, (pixel.y / TILE) * tilesPerRow + pixel.x / TILE).xy;
  int first = int(range.x);
  // Front to back: each shape adds its colour times its covered share of what still shows
  // (transmittance), until an opaque shape covers every sample. The share times the shape's
  // alpha / 255 is rounded to 8 bits as the triangle path's alpha is (n · alpha is a whole number,
  // exact, and for alpha 255 the same operations as before alpha was recorded); its framebuffer
  // also rounds after every blend, which this does not, hence differences of a unit or two where
  // shapes overlap partly (tests/test_render_tiles.cpp).
  vec3 color = vec3(0.0);
  float transmitted = 1.0;
  for (int i = int(range.y) - 1; i >= 0 && transmitted > 0.0; --i) {
    vec3 shapeColor;
    float opacity;
    int n = coveredSamples(int(texelFetch(items, first + i).x), c, shapeColor, opacity);
    float alpha = floor(float(n) * opacity / float(SAMPLE_COUNT) + 0.5) / 255.0;
    color += transmitted * alpha * shapeColor;
    transmitted *= 1.0 - alpha;
  }
  color += transmitted * backgroundAlpha * background;
  fragColor = vec4(floor(color + 0.5) / 255.0, 1.0 - transmitted * (1.0 - backgroundAlpha));
}
)";

// Which texture buffer holds what, and its texel format.
constexpr GLenum kFormats[3] = {GL_RGBA32F, GL_RG32UI, GL_R32UI};
constexpr const char* kSamplers[3] = {"shapes", "tiles", "items"};

}  // namespace

TileProgram::TileProgram(const GlFunctions& gl, int samples, int width, int height, bool flipY) : gl_(gl) {
  const std::string header = std::string("#version 330\n#define FLIP_Y ") + (flipY ? "true" : "false") +
                             "\n#define TILE " + std::to_string(kTileSizePx) + "\n#define FAR " +
                             std::to_string(kFarPx) + "\n#define KIND_ANNULUS " + std::to_string(kAnnulusKind) + "\n" +
                             samplePatternGlsl(samples);
  const std::string flip = std::string("#version 330\n#define FLIP_Y ") + (flipY ? "true" : "false") + "\n";
  program_ = linkProgram(gl, flip + kTileVertexShader, header + kTileFragmentShader);
  positionAttr_ = gl.glGetAttribLocation(program_, "position");
  gl.glUseProgram(program_);
  gl.glGenBuffers(3, buffers_);
  gl.glGenTextures(3, textures_);
  for (int i = 0; i < 3; ++i) gl.glUniform1i(gl.glGetUniformLocation(program_, kSamplers[i]), i);
  gl.glUniform1f(gl.glGetUniformLocation(program_, "imageHeight"), float(height));
  gl.glUniform2f(gl.glGetUniformLocation(program_, "imageSize"), float(width), float(height));
  backgroundUniform_ = gl.glGetUniformLocation(program_, "background");
  backgroundAlphaUniform_ = gl.glGetUniformLocation(program_, "backgroundAlpha");
  tilesPerRowUniform_ = gl.glGetUniformLocation(program_, "tilesPerRow");
  GLint most = 0;
  gl.glGetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &most);
  maxTexels_ = most;
  checkGl(gl, "tile program setup");
}

bool TileProgram::fits(const TileBins& bins) const {
  return 4 * (long long)bins.shapes().size() <= maxTexels_ && (long long)bins.items().size() <= maxTexels_ &&
         (long long)bins.tiles().size() / 2 <= maxTexels_;
}

void TileProgram::draw(const TileBins& bins, Rgb background, bool transparent) const {
  const GlFunctions& gl = gl_;
  gl.glUseProgram(program_);
  gl.glUniform1i(tilesPerRowUniform_, bins.tilesPerRow());
  gl.glUniform3f(backgroundUniform_, float(background.r), float(background.g), float(background.b));
  gl.glUniform1f(backgroundAlphaUniform_, transparent ? 0.0f : 1.0f);
  // GL needs a buffer of at least one texel; an empty frame binds one zero.
  static const std::uint32_t kZero[4] = {0, 0, 0, 0};
  const void* data[3] = {bins.shapes().data(), bins.tiles().data(), bins.items().data()};
  const size_t bytes[3] = {bins.shapes().size() * sizeof(ShapeRecord), bins.tiles().size() * sizeof(std::uint32_t),
                           bins.items().size() * sizeof(std::uint32_t)};
  for (int i = 0; i < 3; ++i) {
    gl.glActiveTexture(GL_TEXTURE0 + i);
    gl.glBindBuffer(GL_TEXTURE_BUFFER, buffers_[i]);
    // The store grows (by half again, so a growing scene reallocates rarely) and is otherwise
    // refilled in place: the previous frame was read back, so GL no longer reads it, and a new
    // store each frame would cost its page faults again (a 300,000-shape frame's are 19 MB). The
    // first store is the first frame's size: most scenes keep their shape count, and a half
    // spare was 96 MB of the million-particle cloth's shapes alone.
    const size_t size = bytes[i] ? bytes[i] : sizeof kZero;
    if (size > capacity_[i]) {
      capacity_[i] = capacity_[i] == 0 ? size : size + size / 2;
      gl.glBufferData(GL_TEXTURE_BUFFER, GLsizeiptr(capacity_[i]), nullptr, GL_DYNAMIC_DRAW);
      gl.glBindTexture(GL_TEXTURE_BUFFER, textures_[i]);
      gl.glTexBuffer(GL_TEXTURE_BUFFER, kFormats[i], buffers_[i]);
    } else {
      gl.glBindTexture(GL_TEXTURE_BUFFER, textures_[i]);
    }
    gl.glBufferSubData(GL_TEXTURE_BUFFER, 0, GLsizeiptr(size), bytes[i] ? data[i] : kZero);
  }
  gl.glActiveTexture(GL_TEXTURE0);
  gl.glBindBuffer(GL_TEXTURE_BUFFER, 0);
  gl.glDisable(GL_BLEND);  // each pixel is written whole; GlContext::beginFrame enables blending again
  // Only the runs of tiles with shapes are drawn: the rest keeps the cleared background, and
  // costs nothing (llvmpipe runs a loop's body at least once per pixel, shapes or not).
  if (!bins.runs().empty() && positionAttr_ >= 0) {
    gl.glEnableVertexAttribArray(GLuint(positionAttr_));
    gl.glVertexAttribPointer(GLuint(positionAttr_), 2, GL_FLOAT, GL_FALSE, 0, bins.runs().data());
    gl.glDrawArrays(GL_TRIANGLES, 0, GLsizei(bins.runs().size() / 2));
  }
  if (positionAttr_ >= 0) gl.glDisableVertexAttribArray(GLuint(positionAttr_));
}

}  // namespace particles::render
