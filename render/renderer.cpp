#include "render/renderer.hpp"

#include "render/frame_mesh.hpp"
#include "render/gl_context.hpp"
#include "render/shader_program.hpp"
#include "render/shape_mesh.hpp"

namespace particles::render {

struct Renderer::Impl {
  // Members in the order they are made: the program is compiled in the context, current once made.
  RenderOptions options;
  Theme colors;
  std::unique_ptr<GlContext> context;
  ShaderProgram program;
  ShapeMesh mesh;  // the frame's triangles, storage reused from frame to frame

  Impl(const RenderOptions& o, const GlRequest& gl)
      : options(o),
        colors(theme(o.themeName)),
        context(makeGlContext(gl, o.width, o.height)),
        program(context->gl(), o.msaa, o.width, o.height, context->flipsY()) {}
};

Renderer::Renderer(const RenderOptions& options, const GlRequest& gl) {
  validate(options);
  impl_ = std::make_unique<Impl>(options, gl);
}

Renderer::~Renderer() = default;  // the context owns the program; destroying it frees both

const RenderOptions& Renderer::options() const {
  return impl_->options;
}
int Renderer::samples() const {
  return impl_->options.msaa;
}
const GlInfo& Renderer::gl() const {
  return impl_->context->info();
}

const Image& Renderer::render(const Drawing& frame, const Camera& camera) {
  Impl& m = *impl_;
  buildFrameMesh(frame, camera, m.options, m.colors, m.mesh);
  m.context->beginFrame(m.colors.background);
  m.program.draw(m.mesh);
  return m.context->finishFrame();
}

}  // namespace particles::render
