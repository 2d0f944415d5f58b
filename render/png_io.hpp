#pragma once
// PNG files through libpng: a single frame (`particles render … -o file.png --at T`), reading one
// back (tests, the golden-frame comparison), and numbered frame sequences (PngSequenceWriter in
// frame_writer.hpp).
//
// Frames are written as 8-bit RGB (alpha dropped: the renderer's frames are opaque), or as 8-bit RGBA
// with PngOptions::alpha (a transparent background, RenderOptions::transparentBackground).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "render/image.hpp"

namespace particles::render {

struct PngOptions {
  // zlib level 0 (store) to 9 (smallest). 6 is zlib's own default: on a cloth frame as fast as
  // level 1 with smaller files, and 9 is three times slower for a few per cent (bench/README.md, "PNG level").
  int compressionLevel = 6;
  // Keep the image's alpha (straight, as PNG defines it): RGBA instead of RGB.
  bool alpha = false;
};

// Writes the image to `path` through output::PendingOutput: the file appears only when complete,
// an existing one is replaced only then, a device or FIFO is written in place, a directory is
// refused. Throws OutputError naming the failing call; no file is left on failure.
void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options = {});

// The PNG file's bytes, in memory (a notebook's inline image, a web server's reply). Throws
// OutputError when libpng fails, std::bad_alloc when the memory runs out.
std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options = {});

// Writes to exactly `path`, no temporary name (for writers that manage their own temporaries).
void writePngDirect(const std::filesystem::path& path, const Image& image, const PngOptions& options);

// Reads any 8-bit or 16-bit PNG as RGBA8 (grey, palette and 16-bit converted; alpha 255 if absent).
// Throws OutputError naming the file and libpng's message, OutOfMemory (render/errors.hpp) when the
// pixels cannot be allocated.
Image readPng(const std::filesystem::path& path);

struct PngSize {
  int width = 0, height = 0;
  bool operator==(const PngSize&) const = default;
};
// The size of a PNG from its header, with readPng's checks on it, without decoding (or allocating)
// its pixels: what an image of it would take, w · h · 4 bytes. Throws as readPng.
PngSize readPngSize(const std::filesystem::path& path);
// The same from the bytes of a PNG file in memory; `name` labels messages.
Image readPngBytes(std::span<const std::uint8_t> bytes, const std::string& name = "PNG data");
// Its size from the header, as readPngSize.
PngSize readPngBytesSize(std::span<const std::uint8_t> bytes, const std::string& name = "PNG data");

}  // namespace particles::render
