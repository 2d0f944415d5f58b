// particles::Renderer and particles::Image: see include/particles/renderer.hpp.
#include <particles/renderer.hpp>

#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>

#include "api/checked_image.hpp"
#include "input/printable_text.hpp"
#include "api/exclusive_use.hpp"
#include "api/guarded_call.hpp"
#include "api/simulation_impl.hpp"
#include "core/drawing.hpp"
#include "core/worker_pool.hpp"
#include "render/gl_backend.hpp"
#include "render/png_io.hpp"
#include "render/renderer.hpp"
#include "render/styled_run.hpp"

namespace particles {

namespace {

// Sets one look option through the command line's own row (render/render_options.hpp), so that a
// setting means here what it means to `particles render`.
void readLook(render::RenderOptions& look, std::string_view flag, std::string_view setting, const std::string& text) {
  const render::LookOption& row = render::lookOption(flag);
  if (!row.read(text, look)) {
    throw ArgumentError(
        fmt::format("Renderer: {} (as {}) takes {}, not {}", setting, flag, row.expected, input::quotedValue(text)));
  }
}

// Whether a renderer made with `made` draws frames of `wanted`: the settings are the Renderer's, and
// the size, particle radius and spring width what a style makes of them (StyledRun::look).
bool drawsAs(const render::RenderOptions& made, const render::RenderOptions& wanted) {
  return made.width == wanted.width && made.height == wanted.height &&
         made.particleRadius.value == wanted.particleRadius.value &&
         made.particleRadius.unit == wanted.particleRadius.unit && made.springWidthPx == wanted.springWidthPx;
}

}  // namespace

struct Renderer::Impl {
  render::RenderOptions look;  // the size is set per frame
  bool sizeGiven = false;
  render::GlRequest gl;
  std::unique_ptr<render::Renderer> renderer;  // made at the first frame, again for a new size
  unsigned madeAtFork = 0;                     // forkCount() when `renderer` was made

  // A renderer made before this process was forked: its GL context's threads (llvmpipe's) stayed in
  // the parent, and freeing it would wait for them forever. It is left as it is, never used or freed
  // here, and the next frame makes one of this process's own.
  void forgetInheritedRenderer() {
    if (renderer && madeAtFork != forkCount()) (void)renderer.release();
  }
  ~Impl() { forgetInheritedRenderer(); }
  render::StyledFrameBuffers buffers;         // the frame's, its storage reused from frame to frame
  std::atomic<bool> busy{false};              // a frame is being drawn (ExclusiveUse)
};

Renderer::Renderer(const RenderSettings& settings) {
  impl_ = api::guardedCall("Renderer", [&] {
    auto impl = std::make_unique<Impl>();
    if ((settings.width == 0) != (settings.height == 0)) {
      throw ArgumentError(fmt::format("Renderer: give both width and height, or neither (the scenario's size); got {}x{}",
                                      settings.width, settings.height));
    }
    impl->sizeGiven = settings.width != 0;
    if (impl->sizeGiven) readLook(impl->look, "--size", "width and height", fmt::format("{}x{}", settings.width, settings.height));
    readLook(impl->look, "--msaa", "msaa", fmt::format("{}", settings.msaa));
    // The choices through their command-line names, read by the command's own rows: the same
    // checks (a value outside the enum, cast in by a careless caller, is refused there).
    readLook(impl->look, "--theme", "theme", std::string(particles::name(settings.theme)));
    readLook(impl->look, "--background", "background", std::string(particles::name(settings.background)));
    readLook(impl->look, "--raster", "raster", std::string(particles::name(settings.raster)));
    if (particles::name(settings.gl).empty()) throw ArgumentError("Renderer: gl is not a GlBackend");
    render::validate(impl->look);  // the size's range, as well as the rest
    impl->gl.backend = settings.gl;
    impl->gl.gpu = settings.gpu;
    render::validate(impl->gl);
    return impl;
  });
}
Renderer::Renderer(Renderer&& other) noexcept = default;
Renderer& Renderer::operator=(Renderer&& other) noexcept = default;
Renderer::~Renderer() = default;

Image Renderer::render(const Simulation& simulation) {
  return api::guardedCall("Renderer::render", [&] {
    if (!impl_) throw ArgumentError("Renderer::render: this Renderer was moved from");
    if (!simulation.impl_) throw ArgumentError("Renderer::render: the Simulation was moved from");
    Simulation::Impl& sim = *simulation.impl_;
    ExclusiveUse drawing(impl_->busy, "Renderer::render", "Renderer");
    ExclusiveUse use(sim.busy, "Renderer::render");
    if (!sim.historyError.empty()) throw Error(fmt::format("Renderer::render: {}", sim.historyError));
    const scenario::Scenario& s = sim.scenario;
    if (!impl_->sizeGiven) {
      impl_->look.width = s.render.width;
      impl_->look.height = s.render.height;
    }
    render::validate(impl_->look);
    // As `particles render --at` draws its one frame (render/styled_run.hpp): the style's automatic
    // ranges and fitted camera are the frame's own, its trails and followed camera the simulation's
    // history since its start.
    render::StyledRun styled(s.style, s.render.view, render::Camera{s.render.viewCenter, s.render.viewHeight},
                             impl_->look, sim.history.get());
    impl_->forgetInheritedRenderer();
    if (!impl_->renderer || !drawsAs(impl_->renderer->options(), styled.look())) {
      impl_->renderer.reset();
      impl_->renderer = std::make_unique<render::Renderer>(styled.look(), impl_->gl);
      impl_->madeAtFork = forkCount();
    }
    // A large frame's shapes are built on the simulation's threads, idle while it is drawn (it is
    // this call's: `use` above).
    const render::Image& frame =
        render::drawStyledFrame(sim.system(), styled, *impl_->renderer, impl_->buffers, true, sim.system().pool());
    Image image{frame.width, frame.height, frame.rgba};
    // A program may draw each frame on another thread (a Python thread pool): EGL binds a context
    // to one thread at a time.
    impl_->renderer->releaseFromThread();
    return image;
  });
}

std::string Renderer::glDescription() const {
  if (!impl_ || !impl_->renderer) return {};
  return render::describe(impl_->renderer->gl());
}

render::Image api::checkedImage(const Image& image, std::string_view call, std::string_view noun) {
  if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) {
    throw ArgumentError(fmt::format("{}: a {}x{} {} needs {} bytes of RGBA, it has {}", call, image.width, image.height,
                                    noun, size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) * 4,
                                    image.rgba.size()));
  }
  render::Image out(image.width, image.height);
  out.rgba = image.rgba;
  return out;
}

void Image::savePng(const std::string& path, bool alpha) const {
  api::guardedCall("Image::savePng", [&] {
    render::PngOptions png;
    png.alpha = alpha;
    render::writePng(path, api::checkedImage(*this, "Image::savePng"), png);
  });
}

std::vector<std::uint8_t> Image::encodePng(bool alpha) const {
  return api::guardedCall("Image::encodePng", [&] {
    render::PngOptions png;
    png.alpha = alpha;
    return render::encodePng(api::checkedImage(*this, "Image::encodePng"), png);
  });
}

}  // namespace particles
