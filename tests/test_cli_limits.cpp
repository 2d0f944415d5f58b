// Inputs and outputs too large for memory, and damaged video segments. Memory that runs out is an
// error with exit 3 ("out of memory: …"), never a crash and never exit 1 ("simulation failed",
// "frames differ"); what does not need memory does not take it (compare's sizes from the PNG
// headers, concat's segments one at a time); concat joins only what decodes whole. The runs are
// bounded as tests/test_hostile_input.cpp's are (an address-space cap and a wall-clock guard);
// under AddressSanitizer there is no cap, and the cases that need one are skipped.
#include <doctest/doctest.h>
#include <fmt/format.h>
#include <zlib.h>

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cli_support.hpp"
#include "render/gl_backend.hpp"
#include "render/gl_context.hpp"
#include "skip.hpp"
#include "support/video_probe.hpp"

using namespace particles::test;

namespace {



// A big-endian 32-bit number, as PNG stores them.
void put32(std::string& out, std::uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((v >> shift) & 0xff));
}

void putChunk(std::string& out, const char* type, const std::string& data) {
  put32(out, std::uint32_t(data.size()));
  const std::string typed = std::string(type, 4) + data;
  out += typed;
  put32(out, std::uint32_t(crc32(0, reinterpret_cast<const Bytef*>(typed.data()), uInt(typed.size()))));
}

// A width × height 8-bit grey PNG of one value, deflated row by row at zlib's fastest level: a
// 16384² one is 1.2 MB (260 kB at level 9, in twice the time) and 1 GiB decoded to RGBA.
fs::path writeGreyPng(const fs::path& path, int width, int height, std::uint8_t grey) {
  std::string ihdr;
  put32(ihdr, std::uint32_t(width));
  put32(ihdr, std::uint32_t(height));
  ihdr += std::string("\x08\x00\x00\x00\x00", 5);  // 8 bits, grey, deflate, no filter, not interlaced
  z_stream z{};
  REQUIRE(deflateInit(&z, 1) == Z_OK);
  std::string row(size_t(width) + 1, char(grey)), idat;
  row[0] = 0;  // filter type None
  std::array<unsigned char, 1 << 16> buffer{};
  bool deflated = true;
  for (int y = 0; y < height; ++y) {
    z.next_in = reinterpret_cast<Bytef*>(row.data());
    z.avail_in = uInt(row.size());
    const int flush = y + 1 == height ? Z_FINISH : Z_NO_FLUSH;
    do {
      z.next_out = buffer.data();
      z.avail_out = uInt(buffer.size());
      deflated = deflated && deflate(&z, flush) != Z_STREAM_ERROR;
      idat.append(reinterpret_cast<const char*>(buffer.data()), buffer.size() - z.avail_out);
    } while (z.avail_out == 0 || (flush == Z_FINISH && z.avail_in > 0));
  }
  deflateEnd(&z);
  REQUIRE(deflated);
  std::string png = "\x89PNG\r\n\x1a\n";
  putChunk(png, "IHDR", ihdr);
  putChunk(png, "IDAT", idat);
  putChunk(png, "IEND", "");
  std::ofstream(path, std::ios::binary) << png;
  return path;
}

// Checks what a run that ran out of memory must look like: exit 3 and the message, no crash.
void checkOutOfMemory(const Result& r) {
  CHECK(r.code == 3);
  CHECK_MESSAGE(r.err.rfind("error: out of memory: ", 0) == 0, r.err);
  CHECK(!contains(r.err, "internal error"));
  CHECK(!contains(r.err, "terminate"));
}

}  // namespace

TEST_CASE("a 16384² render under a 2 GiB cap ends in exit 3 (or 2), not SIGSEGV, on every backend") {
  if (kSanitized) return particles::test::skipTest("no address-space cap under ASan: the frame would be drawn");
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  // GL's memory is the subject, so a GL raster is named: the cpu path needs no GL buffer and draws
  // this frame within 2 GiB (its own case below).
  for (const auto backend : {particles::render::GlBackend::egl, particles::render::GlBackend::osmesa}) {
    if (!particles::render::glBackendBuilt(backend)) continue;
    for (const int msaa : {1, 16}) {
      const std::string args =
          fmt::format("render s.yaml -o x.png --at 0.1 --size 16384x16384 --raster resident --gl {} --msaa {}",
                      particles::render::glBackendName(backend), msaa);
      CAPTURE(args);
      Scratch::Usage usage;
      const Result r = s.runBounded(args, usage);
      // 3: the frame's image and Mesa's buffer for it (2 GiB) do not fit; 2: a GL with a smaller
      // largest framebuffer, named with --size.
      CHECK((r.code == 2 || r.code == 3));
      CHECK_MESSAGE(contains(r.err, r.code == 2 ? "--size 16384x16384" : "error: out of memory: a 16384x16384 frame"),
                    r.err);
      CHECK(!fs::exists(s.dir / "x.png"));
    }
  }
}

TEST_CASE("on the cpu path, a 16384² frame under a 1 GiB cap ends in exit 3, naming the frame") {
  if (kSanitized) return particles::test::skipTest("no address-space cap under ASan: the frame would be drawn");
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  for (const int msaa : {1, 16}) {
    const std::string args =
        fmt::format("render s.yaml -o x.png --at 0.1 --size 16384x16384 --raster cpu --msaa {}", msaa);
    CAPTURE(args);
    Scratch::Usage usage;
    const Result r = s.runBounded(args, usage, rlim_t(1) << 30);  // the image alone is 1 GiB
    CHECK(r.code == 3);
    CHECK_MESSAGE(contains(r.err, "error: out of memory: the frame (16384x16384 pixels) needs 1024 MiB"), r.err);
    CHECK(!contains(r.err, "internal error"));
    CHECK(!fs::exists(s.dir / "x.png"));
  }
}

TEST_CASE("a frame over one of the GL's size limits is refused naming the limit") {
  // llvmpipe's limits are the renderer's own largest side (16384), which the options refuse first,
  // so the check is seen here with smaller ones, as a GPU's may be.
  const std::vector<particles::render::GlSizeLimit> limits = {{"GL_MAX_VIEWPORT_DIMS", 16384, 16384},
                                                              {"GL_MAX_RENDERBUFFER_SIZE", 8192, 8192}};
  CHECK(particles::render::frameSizeProblem(8192, 8192, limits).empty());
  CHECK(particles::render::frameSizeProblem(16, 16, limits).empty());
  const std::vector<particles::render::GlSizeLimit> unknown = {{"OSMESA_MAX_WIDTH × OSMESA_MAX_HEIGHT", 0, 0}};
  CHECK(particles::render::frameSizeProblem(16384, 16384, unknown).empty());
  CHECK(particles::render::frameSizeProblem(8193, 16, limits) ==
        "a 8193x16 frame is larger than this OpenGL draws: its GL_MAX_RENDERBUFFER_SIZE is 8192x8192 pixels");
  CHECK(particles::render::frameSizeProblem(16, 16385, limits) ==
        "a 16x16385 frame is larger than this OpenGL draws: its GL_MAX_VIEWPORT_DIMS is 16384x16384 pixels");
}

TEST_CASE("compare tells sizes apart from the PNG headers, and running out of memory is exit 3") {
  Scratch s;
  writeGreyPng(s.dir / "big.png", 16384, 16384, 128);
  writeGreyPng(s.dir / "small.png", 16, 16, 128);
  CHECK(fs::file_size(s.dir / "big.png") < 2'000'000);  // small on disk, 1 GiB decoded

  // Neither frame is decoded: no 1 GiB for the big one's pixels.
  Scratch::Usage usage;
  const Result mismatch = s.runBounded("compare small.png big.png", usage);
  CHECK(mismatch.code == 2);
  CHECK(mismatch.err == "error: small.png and big.png: sizes differ: 16×16 expected, 16384×16384 actual\n");
  if (!kSanitized) CHECK(usage.peakMiB < kMaxPeakMiB);

  // Two decoded 16384² frames are 2 GiB, over the cap: out of memory, not "frames differ" (1).
  if (!kSanitized) {
    const Result same = s.runBounded("compare big.png big.png", usage);
    checkOutOfMemory(same);
    CHECK_MESSAGE(contains(same.err, "big.png"), same.err);
  }
}

TEST_CASE("a simulation that runs out of memory is exit 3, not 'simulation failed'") {
  if (kSanitized) return particles::test::skipTest("no address-space cap under AddressSanitizer");
  Scratch s;
  // A million particles and two million springs: ~565 MiB to run, over a 384 MiB cap in which the
  // program itself starts (under 128 MiB).
  s.write("big.yaml",
          "name: big\n"
          "simulation: {integrator: rk4, dt: 0.01, duration: 0.01}\n"
          "grids:\n"
          "  - {name: g, origin: [0, 0], size: [1000, 1000], spacing: [0.01, 0.01],\n"
          "     springs: {structural: {ks: 10, kd: 0.01}}}\n"
          "forces:\n"
          "  - {type: gravity}\n");
  Scratch::Usage usage;
  const Result r = s.runBounded("run big.yaml", usage, rlim_t(384) << 20);
  checkOutOfMemory(r);
}

TEST_CASE("concat refuses a segment that does not decode whole, naming it, and writes nothing") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o a.mp4 --frames 0:9 --size 64x48 --quiet").code == 0);
  REQUIRE(s.run("render s.yaml -o b.mp4 --frames 0:5 --size 64x48 --quiet").code == 0);
  const std::string a = slurp(s.dir / "a.mp4");
  REQUIRE(a.size() > 2300);
  std::ofstream(s.dir / "cut.mp4", std::ios::binary) << a.substr(0, a.size() - 300);  // its last frames cut short
  std::ofstream(s.dir / "head.mp4", std::ios::binary) << a.substr(0, 2000);           // its index, few frames

  const Result whole = s.run("concat a.mp4 b.mp4 -o joined.mp4");
  REQUIRE_MESSAGE(whole.code == 0, whole.err);
  CHECK(whole.out == "2 segments, 14 frames, 1.4 s → joined.mp4\n");
  CHECK(particles::test::probeVideo(s.dir / "joined.mp4").frames == 14);
  fs::remove(s.dir / "joined.mp4");

  for (const char* args : {"b.mp4 cut.mp4", "cut.mp4 b.mp4", "cut.mp4", "b.mp4 head.mp4", "head.mp4"}) {
    CAPTURE(args);
    const Result r = s.run(std::string("concat ") + args + " -o joined.mp4");
    CHECK(r.code == 2);
    const std::string bad = contains(args, "cut") ? "cut.mp4" : "head.mp4";
    CHECK_MESSAGE(contains(r.err, "error: " + bad + ": truncated or damaged"), r.err);
    CHECK_MESSAGE(!contains(r.err, "pixel format"), r.err);
    CHECK(!fs::exists(s.dir / "joined.mp4"));
  }
}

TEST_CASE("concat opens one segment at a time: 2000 segments join in bounded memory") {
  Scratch s;
  s.write("s.yaml", kSwingScenario);
  REQUIRE(s.run("render s.yaml -o part.mp4 --frames 0:2 --size 64x48 --quiet").code == 0);
  // The memory bound is what needs 2000 segments (every one open at once would be 780 MiB); under
  // ASan, which checks no bound, 200 segments walk the same loop in a tenth of the time.
  const int segments = kSanitized ? 200 : 2000;
  std::string args = "concat";
  for (int i = 0; i < segments; ++i) args += " part.mp4";
  Scratch::Usage usage;
  const Result r = s.runBounded(args + " -o joined.mp4", usage);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK(r.out == fmt::format("{} segments, {} frames, {} s → joined.mp4\n", segments, 2 * segments, segments / 5));
  if (!kSanitized) CHECK(usage.peakMiB < kMaxPeakMiB);
  CHECK(particles::test::probeVideo(s.dir / "joined.mp4").frames == 2 * segments);
}
