#pragma once
// Which GL backend a drawing command uses (render/gl_backend.hpp): --gl NAME, else the environment
// variable PARTICLES_GL (for CI and containers), else auto: EGL when it starts, else OSMesa.

#include <string>

#include "render/gl_backend.hpp"

namespace particles::app {

inline constexpr const char* kGlEnvironmentVariable = "PARTICLES_GL";

// The backend of `option` (--gl's value; empty: not given) or PARTICLES_GL, with `gpu`. Throws
// InputError for an unknown name in PARTICLES_GL (--gl's is CLI11's to refuse), a backend this
// build lacks, or --gpu where there is no EGL to ask.
render::GlRequest glRequestOf(const std::string& option, bool gpu);

// "GL: egl, software device: llvmpipe …": what `render` without --gl draws with, for --version.
// Makes a context to find out; never throws: says why when there is none.
std::string glVersionLine();

}  // namespace particles::app
