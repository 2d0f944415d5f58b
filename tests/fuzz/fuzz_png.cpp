// libFuzzer harness for the PNG reader (`particles compare`, the golden-frame tests): bytes in, an
// RGBA8 image or an OutputError naming libpng's message out. Any other exception escapes and any
// crash aborts: both are findings. How to run it: tests/fuzz/README.md.
#include <cstddef>
#include <cstdint>
#include <span>

#include "render/errors.hpp"
#include "render/png_io.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace particles::render;
  try {
    (void)readPngBytes(std::span<const std::uint8_t>(data, size), "fuzz.png");
  } catch (const OutputError&) {
    // Not a PNG, or one libpng refuses (bad CRC, truncated data, a header past the size limit).
  }
  return 0;
}
