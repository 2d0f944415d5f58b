#pragma once
// Errors at the rendering boundary. Both name the failing call and the library's own message
// (EGL, OSMesa, OpenGL, libavcodec/libavformat, libpng, the file system). The command line maps both
// to exit code 3 ("output failure", docs/physics.md §12).

#include <new>
#include <stdexcept>
#include <string>
#include <utility>

#include "output/output_error.hpp"

namespace particles::render {

// The off-screen GL context or its buffer could not be made (no EGL display, config or device,
// no OSMesa context), or GL reported an error.
class RenderError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The frame asked for is larger than the OpenGL implementation draws (its GL_MAX_VIEWPORT_DIMS,
// GL_MAX_RENDERBUFFER_SIZE or OSMesa's largest buffer): bad input, exit 2. The message names the
// limit; the program adds the option that asked for the size.
class FrameSizeError : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// The memory a frame, an image or its buffers need could not be had: the estimate checked before
// rendering (render/frame_memory.hpp) or an allocation that failed. A std::bad_alloc, so that the
// program reports it as it reports every failed allocation: exit 3, "out of memory: " + what().
class OutOfMemory : public std::bad_alloc {
 public:
  explicit OutOfMemory(std::string message) : message_(std::move(message)) {}
  const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string message_;
};

// A PNG or MP4 output could not be opened, encoded or written (the output room's error; what was
// written is discarded).
using output::OutputError;

}  // namespace particles::render
