#pragma once
// Internal to render/: the EGL backend (render/gl_backend.hpp). No window and no display server:
// the context has no surface and draws into a framebuffer object, an RGBA8 renderbuffer of the
// frame's size as OSMesa's buffer, upside down as Mesa stores OSMesa's (egl_context.cpp says why),
// read back with glReadPixels into the same Image layout.
//
// Which device, in this order of preference:
//   software (the default)  the EGL device with EGL_MESA_device_software (EGL_EXT_platform_device
//                           with EGL_EXT_device_enumeration): always llvmpipe, whatever GPUs the
//                           machine has. Where EGL lists no devices, Mesa's surfaceless platform
//                           (EGL_MESA_platform_surfaceless), kept only if it too chose llvmpipe or
//                           softpipe: it prefers a GPU unless LIBGL_ALWAYS_SOFTWARE=1.
//   gpu                     the first listed device that is not software (a DRM render node, or
//                           NVIDIA's), or the surfaceless platform if it chose a GPU.
// Displays are initialised once and never terminated (egl_context.cpp says why).

#include <memory>

#include "render/gl_context.hpp"

namespace particles::render {

// A compatibility-profile context (OpenGL ≥ 3.0) on the software device, or a hardware one with
// `gpu`, drawing into a width × height RGBA8 framebuffer; current on return; reading frames back
// as `readBack` says (GlRequest::readBack; GlContext::readsAhead). Throws RenderError naming the
// failing call and EGL's error (no display, no config, no context, no such device).
std::unique_ptr<GlContext> makeEglContext(bool gpu, GlRequest::ReadBack readBack, int width, int height);

}  // namespace particles::render
