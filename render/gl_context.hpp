#pragma once
// Internal to render/: an off-screen OpenGL context (OSMesa, Mesa's software rasteriser) drawing
// into an Image it owns. No depth, stencil or accumulation buffers: shapes are drawn in painter's
// order. Image row 0 is the top of the picture.

#include <memory>

#include "render/image.hpp"
#include "render/theme.hpp"

struct osmesa_context;  // OSMesaContext points to one (GL/osmesa.h)

namespace particles::render {

class GlContext {
 public:
  // Makes the context with a width × height colour buffer and makes it current. Throws RenderError
  // naming the failing call (OSMesaCreateContextAttribs, OSMesaMakeCurrent).
  GlContext(int width, int height);
  GlContext(const GlContext&) = delete;
  GlContext& operator=(const GlContext&) = delete;

  // Makes this context current (another renderer may have been drawing in between), sets the
  // state every frame is drawn with (coverage blended as alpha, nothing else) and clears the image
  // to `background`. Throws RenderError.
  void beginFrame(Rgb background);
  // Waits until GL has drawn everything and returns the image. Throws RenderError if GL reported an
  // error since beginFrame.
  const Image& finishFrame();

 private:
  struct ContextDeleter {
    void operator()(osmesa_context* context) const;
  };
  Image image_;  // OSMesa's colour buffer: GL window row y is image row y
  std::unique_ptr<osmesa_context, ContextDeleter> context_;

  void makeCurrent();
};

// Throws RenderError("WHAT: OpenGL error NAME") if GL has recorded an error.
void checkGl(const char* what);

}  // namespace particles::render
