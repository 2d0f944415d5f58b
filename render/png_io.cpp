#include "render/png_io.hpp"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <span>
#include <string>
#include <vector>

#include "output/pending_output.hpp"
#include "render/errors.hpp"
#include "render/frame_memory.hpp"
#include "render/render_options.hpp"

namespace particles::render {

namespace {

// libpng reports errors by longjmp. The calls that can fail sit in small functions below that hold
// nothing with a destructor between setjmp and the calls, so no C++ object is skipped by the jump;
// everything that needs freeing is owned by the callers.
struct PngErrorSink {
  char message[256] = "unknown libpng error";
};

[[noreturn]] void onPngError(png_structp png, png_const_charp msg) {
  auto* sink = static_cast<PngErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", msg);
  png_longjmp(png, 1);
}
void onPngWarning(png_structp, png_const_charp) {}  // e.g. unknown ancillary chunks: harmless

using output::FilePtr;

struct PngWriteDeleter {
  void operator()(png_struct* p) const { png_destroy_write_struct(&p, nullptr); }
};
struct PngReadDeleter {
  void operator()(png_struct* p) const { png_destroy_read_struct(&p, nullptr, nullptr); }
};
struct PngInfoDeleter {  // the info struct is freed through its png_struct, which must outlive it
  png_struct* png;
  void operator()(png_info* i) const { png_destroy_info_struct(png, &i); }
};
using PngWritePtr = std::unique_ptr<png_struct, PngWriteDeleter>;
using PngReadPtr = std::unique_ptr<png_struct, PngReadDeleter>;
using PngInfoPtr = std::unique_ptr<png_info, PngInfoDeleter>;

bool writeRows(png_structp png, png_infop info, std::FILE* file, const Image& image, const PngOptions& options,
               png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_init_io(png, file);
  png_set_compression_level(png, options.compressionLevel);
  png_set_IHDR(png, info, png_uint_32(image.width), png_uint_32(image.height), 8,
               options.alpha ? PNG_COLOR_TYPE_RGBA : PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_write_info(png, info);
  if (!options.alpha) png_set_filler(png, 0, PNG_FILLER_AFTER);  // input rows are RGBA: drop the A byte
  png_write_image(png, rows);
  png_write_end(png, nullptr);
  return true;
}

struct PngHeader {
  png_uint_32 width = 0, height = 0;
  size_t rowBytes = 0;      // after conversion to RGBA8
  size_t fileRowBytes = 0;  // as stored: colour type and bit depth of the file, before conversion
};

bool readHeader(png_structp png, png_infop info, PngHeader* header) {
  if (setjmp(png_jmpbuf(png))) return false;
  // Only IHDR, PLTE, tRNS, IDAT and IEND make the pixels; every other chunk is skipped unread (a
  // negative count means all of them, libpng(3)). libpng 1.6.39 allocates an ancillary chunk's
  // declared length before reading it: a 91-byte file with a zTXt chunk claiming 1.5 GB cost 1.5 GB
  // (found by tests/fuzz/fuzz_png).
  png_set_keep_unknown_chunks(png, PNG_HANDLE_CHUNK_NEVER, nullptr, -1);
  png_read_info(png, info);
  header->fileRowBytes = png_get_rowbytes(png, info);
  const int colorType = png_get_color_type(png, info);
  png_set_expand(png);  // palette → RGB, grey < 8 bits → 8 bits, tRNS → alpha
  png_set_strip_16(png);
  if (colorType == PNG_COLOR_TYPE_GRAY || colorType == PNG_COLOR_TYPE_GRAY_ALPHA) png_set_gray_to_rgb(png);
  if (!(colorType & PNG_COLOR_MASK_ALPHA) && !png_get_valid(png, info, PNG_INFO_tRNS)) {
    png_set_add_alpha(png, 0xff, PNG_FILLER_AFTER);
  }
  png_set_interlace_handling(png);
  png_read_update_info(png, info);
  header->width = png_get_image_width(png, info);
  header->height = png_get_image_height(png, info);
  header->rowBytes = png_get_rowbytes(png, info);
  return true;
}

bool readRows(png_structp png, png_bytepp rows) {
  if (setjmp(png_jmpbuf(png))) return false;
  png_read_image(png, rows);
  png_read_end(png, nullptr);
  return true;
}

// The bytes readPngBytes decodes, handed to libpng as it asks for them.
struct MemoryReader {
  std::span<const std::uint8_t> bytes;
  std::size_t offset = 0;
};

void readFromMemory(png_structp png, png_bytep out, png_size_t length) {
  auto* reader = static_cast<MemoryReader*>(png_get_io_ptr(png));
  if (length > reader->bytes.size() - reader->offset) png_error(png, "unexpected end of data");
  std::memcpy(out, reader->bytes.data() + reader->offset, length);
  reader->offset += length;
}

std::vector<png_bytep> rowPointers(Image& image) {
  std::vector<png_bytep> rows(size_t(image.height));
  for (int y = 0; y < image.height; ++y) rows[size_t(y)] = image.pixel(0, y);
  return rows;
}

// zlib's largest compression ratio ("Maximum Compression Factor", zlib.net/zlib_tech.html): deflate
// codes at most 258 bytes in about 2 bits, so n bytes of IDAT decompress to at most 1032·n.
constexpr std::uintmax_t kMaxDeflateRatio = 1032;

// A PNG whose signature the caller has checked, opened on the source `setSource` gives libpng (a
// FILE* or bytes in memory) of `inputBytes` bytes (UINTMAX_MAX when unknown), with its header read
// and checked: nothing of the pixels is allocated yet. `name` labels messages.
class PngDecoder {
 public:
  PngDecoder(const std::string& name, std::uintmax_t inputBytes, const std::function<void(png_structp)>& setSource)
      : name_(name) {
    png_.reset(png_create_read_struct(PNG_LIBPNG_VER_STRING, &sink_, onPngError, onPngWarning));
    if (!png_) throw OutputError("png_create_read_struct failed for " + name);
    info_ = PngInfoPtr(png_create_info_struct(png_.get()), PngInfoDeleter{png_.get()});
    if (!info_) throw OutputError("png_create_info_struct failed for " + name);
    setSource(png_.get());
    if (!readHeader(png_.get(), info_.get(), &header_)) fail();
    if (header_.rowBytes != size_t(header_.width) * 4) {
      throw OutputError(name + ": unexpected PNG layout after conversion to RGBA8");
    }
    // Checked on the header, before any pixel is allocated: a 68-byte file claiming 20000 × 20000
    // pixels would otherwise cost 1.6 GB first.
    if (header_.width > png_uint_32(kMaxImageSide) || header_.height > png_uint_32(kMaxImageSide)) {
      throw OutputError(name + ": its header claims " + std::to_string(header_.width) + "x" +
                        std::to_string(header_.height) + " pixels; images are at most " +
                        std::to_string(kMaxImageSide) + " pixels a side");
    }
    // A header that claims more pixels than the file could decompress to is refused before the
    // image is allocated too: a 69-byte file claiming 16384 × 16384 would otherwise cost 1 GiB first
    // (found by tests/fuzz/fuzz_png). Every stored row holds at least fileRowBytes − 1 bytes of
    // pixels, interlaced or not.
    const std::uintmax_t pixelBytes = std::uintmax_t(header_.height) * (std::max<size_t>(header_.fileRowBytes, 1) - 1);
    if (inputBytes < std::numeric_limits<std::uintmax_t>::max() / kMaxDeflateRatio &&
        pixelBytes > inputBytes * kMaxDeflateRatio) {
      throw OutputError(name + ": its header claims " + std::to_string(header_.width) + "x" +
                        std::to_string(header_.height) + " pixels, more than its " + std::to_string(inputBytes) +
                        " bytes can hold");
    }
  }

  // libpng holds the address of sink_: the decoder stays where it was made.
  PngDecoder(const PngDecoder&) = delete;
  PngDecoder& operator=(const PngDecoder&) = delete;

  PngSize size() const { return {int(header_.width), int(header_.height)}; }

  // The pixels, as RGBA8. Throws OutOfMemory when the image cannot be allocated.
  Image decode() {
    Image image = allocateImage(int(header_.width), int(header_.height), "decoding " + name_);
    std::vector<png_bytep> rows = rowPointers(image);
    if (!readRows(png_.get(), rows.data())) fail();
    return image;
  }

 private:
  std::string name_;
  PngErrorSink sink_;
  PngReadPtr png_;
  PngInfoPtr info_{nullptr, PngInfoDeleter{nullptr}};
  PngHeader header_;

  [[noreturn]] void fail() const {
    // libpng's own allocations (its row buffers) fail with "Out of memory" (png_malloc).
    if (std::strstr(sink_.message, "Out of memory") != nullptr) {
      throw OutOfMemory("libpng could not read " + name_ + ": " + sink_.message);
    }
    throw OutputError("libpng could not read " + name_ + ": " + sink_.message);
  }
};

bool hasPngSignature(std::span<const std::uint8_t> bytes) {
  return bytes.size() >= 8 && png_sig_cmp(bytes.data(), 0, 8) == 0;
}

void validatePngInput(const Image& image, const PngOptions& options) {
  if (options.compressionLevel < 0 || options.compressionLevel > 9) {
    throw std::invalid_argument("PNG compression level " + std::to_string(options.compressionLevel) +
                                " is out of range 0–9");
  }
  if (image.width < 1 || image.height < 1 || image.rgba.size() != size_t(image.width) * size_t(image.height) * 4) {
    throw std::invalid_argument("writePng: image is empty or its buffer does not match its size");
  }
}

// Encodes the image into `file` and closes it; `path` names it in messages.
void writePngStream(output::FilePtr file, const std::filesystem::path& path, const Image& image,
                    const PngOptions& options) {
  PngErrorSink sink;
  PngWritePtr png(png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, onPngError, onPngWarning));
  if (!png) throw OutputError("png_create_write_struct failed for " + path.string());
  PngInfoPtr info(png_create_info_struct(png.get()), PngInfoDeleter{png.get()});
  if (!info) throw OutputError("png_create_info_struct failed for " + path.string());

  // libpng takes non-const rows; it only reads them when writing.
  std::vector<png_bytep> rows(size_t(image.height));
  for (int y = 0; y < image.height; ++y) rows[size_t(y)] = const_cast<png_bytep>(image.pixel(0, y));
  if (!writeRows(png.get(), info.get(), file.get(), image, options, rows.data())) {
    throw OutputError("libpng could not write " + path.string() + ": " + sink.message);
  }
  // fclose flushes: a full disk shows up here, so its result counts.
  if (std::fclose(file.release()) != 0) {
    throw OutputError("cannot finish writing " + path.string() + ": " + std::strerror(errno));
  }
}

}  // namespace

void writePngDirect(const std::filesystem::path& path, const Image& image, const PngOptions& options) {
  validatePngInput(image, options);
  FilePtr file(std::fopen(path.c_str(), "wb"));
  if (!file) throw OutputError("cannot open " + path.string() + " for writing: " + std::strerror(errno));
  writePngStream(std::move(file), path, image, options);
}

std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options) {
  validatePngInput(image, options);
  // open_memstream grows its buffer as libpng writes and sets buffer and size at fclose; the
  // buffer is freed after the stream is closed, on failure too (declared before it).
  char* buffer = nullptr;
  std::size_t size = 0;
  const std::unique_ptr<char*, void (*)(char**)> freeBuffer(&buffer, [](char** b) { std::free(*b); });
  FilePtr file(open_memstream(&buffer, &size));
  if (!file) {
    if (errno == ENOMEM) throw std::bad_alloc();
    throw OutputError(std::string("open_memstream failed: ") + std::strerror(errno));
  }
  writePngStream(std::move(file), "the PNG in memory", image, options);
  return std::vector<std::uint8_t>(buffer, buffer + size);
}

void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options) {
  validatePngInput(image, options);
  output::PendingOutput out(path);
  writePngStream(out.openStream(), path, image, options);
  out.commit();
}

namespace {

// Opens `path` as a PNG and reads its header (PngDecoder); `file` keeps the stream open for it.
PngDecoder openPng(const std::filesystem::path& path, FilePtr& file) {
  file.reset(std::fopen(path.c_str(), "rb"));
  if (!file) throw OutputError("cannot open " + path.string() + ": " + std::strerror(errno));
  std::uint8_t signature[8];
  const std::size_t got = std::fread(signature, 1, 8, file.get());
  if (!hasPngSignature({signature, got})) throw OutputError(path.string() + " is not a PNG file");
  std::rewind(file.get());
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);  // unknown for a pipe: no check
  std::FILE* stream = file.get();
  return PngDecoder(path.string(), ec ? std::numeric_limits<std::uintmax_t>::max() : size,
                    [&](png_structp png) { png_init_io(png, stream); });
}

}  // namespace

Image readPng(const std::filesystem::path& path) {
  FilePtr file;
  return openPng(path, file).decode();
}

PngSize readPngSize(const std::filesystem::path& path) {
  FilePtr file;
  return openPng(path, file).size();
}

namespace {

PngDecoder openPngBytes(std::span<const std::uint8_t> bytes, const std::string& name, MemoryReader& reader) {
  if (!hasPngSignature(bytes)) throw OutputError(name + " is not a PNG file");
  return PngDecoder(name, bytes.size(), [&](png_structp png) { png_set_read_fn(png, &reader, readFromMemory); });
}

}  // namespace

Image readPngBytes(std::span<const std::uint8_t> bytes, const std::string& name) {
  MemoryReader reader{bytes};
  return openPngBytes(bytes, name, reader).decode();
}

PngSize readPngBytesSize(std::span<const std::uint8_t> bytes, const std::string& name) {
  MemoryReader reader{bytes};
  return openPngBytes(bytes, name, reader).size();
}

}  // namespace particles::render
