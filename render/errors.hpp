#pragma once
// Errors at the rendering boundary. Both name the failing call and the library's own message
// (EGL, OSMesa, OpenGL, libavcodec/libavformat, libpng, the file system). The command line maps both
// to exit code 3 ("output failure", docs/physics.md §12).

#include <stdexcept>
#include <string>

#include "output/output_error.hpp"

namespace particles::render {

// The off-screen GL context or its buffer could not be made (no EGL display, config or device,
// no OSMesa context), or GL reported an error.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A PNG or MP4 output could not be opened, encoded or written (the output room's error; what was
// written is discarded).
using output::OutputError;

}  // namespace particles::render
