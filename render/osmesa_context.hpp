#pragma once
// Internal to render/: the OSMesa backend (render/gl_backend.hpp). OSMesa is Mesa's off-screen
// library: llvmpipe draws straight into the context's Image, no framebuffer object or read-back.
// Mesa 25.1 removed it; builds without it: -DPARTICLES_WITH_OSMESA=OFF.

#include <memory>

#include "render/gl_context.hpp"

namespace particles::render {

// A compatibility-profile context drawing into a width × height RGBA8 image, current on return.
// Throws RenderError naming the failing call (OSMesaCreateContextAttribs, OSMesaMakeCurrent).
std::unique_ptr<GlContext> makeOsMesaContext(int width, int height);

}  // namespace particles::render
