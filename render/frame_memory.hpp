#pragma once
// Internal to render/: the memory a frame needs, checked before it is drawn, so that a frame too
// large for the machine (or for an address-space cap, `ulimit -v`, `prlimit --as`) ends in
// OutOfMemory (render/errors.hpp: exit 3, "out of memory: …") and never in a crash. Mesa does not
// say when it cannot allocate a frame's colour buffer: OSMesa's failed silently and glFinish then
// copied from nothing (SIGSEGV), EGL's renderbuffer showed as an "incomplete" framebuffer,
// and glReadPixels took a whole frame of scratch. So our own images are allocated up front,
// and the memory Mesa will take is reserved with them, before the GL context is made, and given
// back right before Mesa allocates.
//
// What a frame of w × h pixels takes, B = 4·w·h bytes: the image it is read into (B), Mesa's colour
// buffer (B), and with EGL the scratch glReadPixels reads through, which was a whole frame (B) and
// is now a strip of at most 32 MiB (render/egl_context.cpp). Measured with `prlimit --as` at 8192²
// (B = 256 MiB; a 16 × 16 frame needs ~480 MiB of address space, mostly libraries and llvmpipe's
// threads): EGL needed a 1400 MiB cap before and 1100 MiB now, OSMesa 1200 MiB before and 1000 MiB
// now. The anti-aliasing takes nothing per pixel (render/renderer.hpp: samples are tested in the
// shader, there is no multisampled buffer), so --msaa does not change it. A transparent background
// or an overlay adds a copy of the frame (B), allocated up front with allocateImage; the tile path
// a table of 8 bytes per 4 × 4 px tile (B / 8) on the CPU and in GL, whose failures are a
// std::bad_alloc and GL_OUT_OF_MEMORY. The cpu path (render/tile_composite.hpp) draws into an image
// of its own (B), allocated with allocateImage at its first frame, and the tile table on the CPU only.

#include <cstddef>
#include <string>

#include "render/image.hpp"

namespace particles::render {

// The bytes of one RGBA8 frame of width × height pixels.
std::size_t frameBytes(int width, int height);

// Memory mapped (not touched, so it costs no RAM) and held for someone else to allocate later:
// under an address-space cap the process can then not spend it on other things meanwhile
// (llvmpipe's threads' heaps, which take whatever the cap leaves), and giving it back right before
// Mesa allocates is what lets Mesa's allocation succeed. Without a cap, the kernel's overcommit
// heuristic refuses a mapping beyond its RAM and swap.
class MemoryReservation {
 public:
  MemoryReservation() = default;
  // Throws OutOfMemory("{what} needs {N} MiB, more than …") when `bytes` cannot be mapped.
  MemoryReservation(std::size_t bytes, const std::string& what);
  ~MemoryReservation();
  MemoryReservation(MemoryReservation&& other) noexcept;
  MemoryReservation& operator=(MemoryReservation&& other) noexcept;
  std::size_t bytes() const { return address_ ? bytes_ : 0; }

 private:
  void* address_ = nullptr;
  std::size_t bytes_ = 0;
};

// A width × height image, its pixels allocated now; throws OutOfMemory naming `what` (e.g. "the
// frame") when they cannot be.
Image allocateImage(int width, int height, const std::string& what);

}  // namespace particles::render
