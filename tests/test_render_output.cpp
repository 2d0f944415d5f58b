// Outputs (render/png_io.hpp, render/video/frame_writer.hpp): PNG round trip, H.264 MP4 decoded back
// through libavformat, PNG sequences, and what is left on disk when things go wrong.

#include <doctest/doctest.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "core/drawing.hpp"
#include "core/solver.hpp"
#include "core/system.hpp"
#include "render/errors.hpp"
#include "render/video/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/video/png_sequence_writer.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"
#include "support/video_probe.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::probeVideo;
using particles::test::ScratchDir;
using particles::test::VideoInfo;

namespace {

RenderOptions outputRenderOptions(bool transparent = false) {
  RenderOptions o = particles::test::smallRenderOptions(320, 180);
  o.transparentBackground = transparent;
  return o;
}

const Camera camera{Vec2(0.1, -0.2), 2.4};

// Renders `count` frames of the falling particles at `fps` into the writer, as the command line
// will: frame i at t = i / fps.
std::vector<Image> renderInto(FrameWriter& writer, long count, int fps, bool keep = false, bool transparent = false) {
  System system = particles::test::fallingParticles();
  Solver solver(Integrator::rk4);
  Renderer renderer(outputRenderOptions(transparent));
  std::vector<Image> kept;
  for (long i = 0; i < count; ++i) {
    while (system.time() < double(i) / fps - 1e-9) solver.doStep(system, 1.0 / (4.0 * fps));
    const Image& image = renderer.render(system.draw(), camera);
    if (keep) kept.push_back(image);
    writer.write(image);
  }
  return kept;
}

FrameWriterOptions writerOptions(int fps) {
  FrameWriterOptions o;
  o.width = 320;
  o.height = 180;
  o.video.fps = fps;
  return o;
}

std::string contents(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// readPngBytes over the bytes of a file held in a string.
Image readPngText(const std::string& bytes, const std::string& name = "test.png") {
  return readPngBytes({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()}, name);
}

double meanAbsoluteDifference(const Image& a, const Image& b) {
  REQUIRE(a.rgba.size() == b.rgba.size());
  double sum = 0;
  for (size_t i = 0; i < a.rgba.size(); i += 4) {
    for (size_t k = 0; k < 3; ++k) sum += std::abs(int(a.rgba[i + k]) - int(b.rgba[i + k]));
  }
  return sum / double(a.rgba.size() / 4 * 3);
}

// `frames` frames of the falling particles at `fps` written to `path` (finished); the frames as rendered.
std::vector<Image> writeVideo(const std::filesystem::path& path, long frames, int fps, const FrameWriterOptions& o,
                              bool transparent = false) {
  auto writer = openFrameWriter(path, o);
  std::vector<Image> rendered = renderInto(*writer, frames, fps, true, transparent);
  CHECK(writer->framesWritten() == frames);
  writer->finish();
  return rendered;
}

// The decoded last frame is the last rendered one (not the first, not blank): it differs from its
// source by compression (under `maxError` levels on average) far less than the frames differ.
void checkLastFrame(const VideoInfo& info, const std::vector<Image>& rendered, double maxError) {
  REQUIRE(info.sample.width == rendered.back().width);
  const double error = meanAbsoluteDifference(info.sample, rendered.back());
  CHECK(error < maxError);
  CHECK(error < meanAbsoluteDifference(rendered.front(), rendered.back()) / 4);
}

}  // namespace

TEST_CASE("a run renders duration × fps frames, and an output's kind and a frame's index are read from their names") {
  CHECK(frameCount(10.0, 60) == 600);
  CHECK(frameCount(0.5, 24) == 12);
  CHECK(frameCount(0.001, 30) == 1);
  CHECK(outputFormatOf("a/b/out.mp4").kind == OutputKind::mp4);
  CHECK(outputFormatOf("OUT.MP4").kind == OutputKind::mp4);
  CHECK(outputFormatOf("frame.png").kind == OutputKind::png);
  CHECK(outputFormatOf("frames/").kind == OutputKind::pngSequence);
  CHECK(outputFormatOf("a/out.gif").kind == OutputKind::gif);
  CHECK(outputFormatOf("OUT.WebM").kind == OutputKind::webm);
  CHECK_THROWS_AS(outputFormatOf("out.avi"), std::invalid_argument);
  // The error lists every format there is.
  try {
    outputFormatOf("out.mkv");
    FAIL("out.mkv accepted");
  } catch (const std::invalid_argument& e) {
    for (const OutputFormat& format : outputFormats()) {
      CHECK_MESSAGE(std::string(e.what()).find(format.example) != std::string::npos, e.what());
    }
  }
  CHECK(sequenceFrameName(42) == "frame_000042.png");
  CHECK(sequenceFrameIndex("frame_000042.png") == 42);
  CHECK(sequenceFrameIndex("frame_1234567.png") == 1234567);
  CHECK_FALSE(sequenceFrameIndex("frame_42.png"));
  CHECK_FALSE(sequenceFrameIndex("frame_00004x.png"));
  CHECK_FALSE(sequenceFrameIndex("frame_000042.png.bak"));
}

TEST_CASE("a rendered frame survives a PNG round trip through libpng") {
  ScratchDir dir;
  setLibavVerbose(false);
  System system = particles::test::fallingParticles();
  Renderer renderer(outputRenderOptions());
  const Image frame = renderer.render(system.draw(), camera);

  writePng(dir / "frame.png", frame, {.compressionLevel = 9});
  writePng(dir / "stored.png", frame, {.compressionLevel = 0});
  CHECK(dir.entries() == std::set<std::string>{"frame.png", "stored.png"});  // no temporaries left
  CHECK(readPng(dir / "frame.png") == frame);
  CHECK(readPng(dir / "stored.png") == frame);
  CHECK(readPngText(contents(dir / "frame.png")) == frame);  // the same from memory
  CHECK(std::filesystem::file_size(dir / "stored.png") > 2 * std::filesystem::file_size(dir / "frame.png"));
  CHECK_THROWS_AS(writePng(dir / "x.png", frame, {.compressionLevel = 10}), std::invalid_argument);
  CHECK_THROWS_AS(readPng(dir / "missing.png"), OutputError);
}

TEST_CASE("an MP4 decodes as H.264 yuv420p with fps × duration frames") {
  ScratchDir dir;
  setLibavVerbose(false);
  for (const auto& [fps, duration] : {std::pair{30, 1.0}, std::pair{24, 0.5}}) {
    CAPTURE(fps);
    const long frames = frameCount(duration, fps);
    const auto path = dir / ("out" + std::to_string(fps) + ".mp4");
    const std::vector<Image> rendered = writeVideo(path, frames, fps, writerOptions(fps));
    const VideoInfo info = probeVideo(path, frames - 1);
    particles::test::checkVideo(info, "h264", 320, 180, frames);
    CHECK(info.pixelFormat == "yuv420p");
    CHECK(info.fps == doctest::Approx(fps));
    CHECK(std::abs(info.durationSeconds - duration) <= 1.0 / fps);
    checkLastFrame(info, rendered, 2.0);
  }
  CHECK(dir.entries() == std::set<std::string>{"out24.mp4", "out30.mp4"});
}

TEST_CASE("MP4 needs an even size and known x264 settings") {
  ScratchDir dir;
  FrameWriterOptions o = writerOptions(30);
  o.width = 321;
  try {
    openFrameWriter(dir / "odd.mp4", o);
    FAIL("odd width accepted");
  } catch (const std::invalid_argument& e) {
    CHECK(std::string(e.what()).find("322x180") != std::string::npos);
  }
  o = writerOptions(30);
  o.video.preset = "fastest";
  CHECK_THROWS_AS(openFrameWriter(dir / "p.mp4", o), std::invalid_argument);
  o = writerOptions(30);
  o.video.crf = 52;
  CHECK_THROWS_AS(openFrameWriter(dir / "c.mp4", o), std::invalid_argument);
  CHECK(dir.entries().empty());
}

TEST_CASE("an unwritable output is a clear error and leaves no file") {
  ScratchDir dir;
  setLibavVerbose(false);
  std::ofstream(dir / "plain_file") << "x";
  const Image frame = Renderer(outputRenderOptions()).render(Drawing{}, camera);
  for (const auto& path : {dir / "missing" / "out.mp4", dir / "plain_file" / "out.mp4"}) {
    CAPTURE(path);
    try {
      openFrameWriter(path, writerOptions(30));
      FAIL("opened");
    } catch (const OutputError& e) {
      const std::string what = e.what();
      CHECK(what.find("cannot write " + path.string()) != std::string::npos);
      CHECK((what.find("No such file") != std::string::npos || what.find("Not a directory") != std::string::npos));
    }
  }
  CHECK_THROWS_WITH_AS(writePng(dir / "missing" / "f.png", frame), doctest::Contains("cannot write"), OutputError);
  CHECK_THROWS_AS(openFrameWriter(dir / "missing" / "deeper" / "", writerOptions(30)), OutputError);
  CHECK_THROWS_AS(openFrameWriter(dir / "plain_file" / "", writerOptions(30)), OutputError);
  CHECK(dir.entries() == std::set<std::string>{"plain_file"});
}

TEST_CASE("an existing output is replaced only on success") {
  ScratchDir dir;
  setLibavVerbose(false);
  const auto path = dir / "out.mp4";
  std::ofstream(path) << "previous run";

  {  // aborted, as the command line does on SIGINT
    auto writer = openFrameWriter(path, writerOptions(30));
    renderInto(*writer, 5, 30);
    writer->abort();
    writer->abort();  // idempotent
    CHECK_THROWS_AS(writer->finish(), std::logic_error);
  }
  CHECK(contents(path) == "previous run");
  CHECK(dir.entries() == std::set<std::string>{"out.mp4"});

  {  // dropped without finish(): an exception unwinding the frame loop
    auto writer = openFrameWriter(path, writerOptions(30));
    renderInto(*writer, 5, 30);
  }
  CHECK(contents(path) == "previous run");
  CHECK(dir.entries() == std::set<std::string>{"out.mp4"});

  {  // a frame of the wrong size is refused before it reaches the encoder
    auto writer = openFrameWriter(path, writerOptions(30));
    CHECK_THROWS_AS(writer->write(Image(16, 16)), std::invalid_argument);
  }
  CHECK(contents(path) == "previous run");

  auto writer = openFrameWriter(path, writerOptions(30));
  renderInto(*writer, 5, 30);
  writer->finish();
  CHECK(probeVideo(path).frames == 5);
  CHECK(dir.entries() == std::set<std::string>{"out.mp4"});
}

TEST_CASE("a PNG sequence holds exactly this run's frames") {
  ScratchDir dir;
  const auto seq = dir / "frames";
  std::filesystem::create_directory(seq);
  std::ofstream(seq / "notes.txt") << "mine";
  std::ofstream(seq / "frame_000007.png") << "stale frame from a longer run";

  auto writer = openFrameWriter(seq / "", writerOptions(30));
  const std::vector<Image> rendered = renderInto(*writer, 4, 30, true);
  writer->finish();
  CHECK(ScratchDir::listing(seq) == std::set<std::string>{"frame_000000.png", "frame_000001.png", "frame_000002.png",
                                                          "frame_000003.png", "notes.txt"});
  for (long i = 0; i < 4; ++i) CHECK(readPng(seq / sequenceFrameName(i)) == rendered[size_t(i)]);
  CHECK(rendered[0] != rendered[3]);

  // Aborted into a directory it created: the directory goes too.
  auto aborted = openFrameWriter(dir / "new" / "", writerOptions(30));
  renderInto(*aborted, 2, 30);
  aborted->abort();
  CHECK(dir.entries() == std::set<std::string>{"frames"});
}

// A 65-byte PNG whose header claims 100000 × 100000 pixels once ended in std::bad_alloc ("internal
// error"), and one claiming 20000 × 20000 allocated 1.6 GB before failing: the header is checked
// against the largest frame before any pixel is allocated.
TEST_CASE("reading a PNG whose header claims more pixels than a frame can have fails before allocating") {
  for (const char* name : {"png_header_100000x100000.png", "png_header_20000x20000.png"}) {
    CAPTURE(name);
    const std::string path = std::string(PARTICLES_SOURCE_DIR) + "/tests/fixtures/" + name;
    REQUIRE(std::ifstream(path).good());
    CHECK_THROWS_WITH_AS(readPng(path), doctest::Contains("pixels; images are at most 16384 pixels a side"),
                         OutputError);
  }
}

// Found by tests/fuzz/fuzz_png: a 69-byte PNG whose header claims 16384 × 16384 RGBA pixels, the
// largest side allowed, over an IDAT of a few bytes, allocated 1 GiB before libpng found the data
// missing. zlib expands n bytes to at most 1032·n, so such a header is refused before allocating.
TEST_CASE("reading a PNG whose header claims more pixels than its bytes can hold fails before allocating") {
  const std::string path = std::string(PARTICLES_SOURCE_DIR) + "/tests/fuzz/corpus/png/side16384_truncated.png";
  REQUIRE(std::ifstream(path).good());
  CHECK_THROWS_WITH_AS(readPng(path), doctest::Contains("16384x16384 pixels, more than its 69 bytes can hold"),
                       OutputError);
  CHECK_THROWS_WITH_AS(readPngText(contents(path), "side.png"),
                       doctest::Contains("side.png: its header claims 16384x16384 pixels, more than its 69 bytes"),
                       OutputError);
}

// Found by tests/fuzz/fuzz_png: libpng allocates an ancillary chunk's declared length before reading
// it, so a 52-byte file whose zTXt chunk claims 1.5 GB cost 1.5 GB of memory before the read failed.
// The reader skips every chunk but those that make the pixels.
TEST_CASE("reading a PNG whose text chunk claims 1.5 GB fails without allocating it") {
  const std::string path = std::string(PARTICLES_SOURCE_DIR) + "/tests/fuzz/corpus/png/ztxt_claiming_1500MB.png";
  REQUIRE(std::ifstream(path).good());
  auto peakKiB = [] {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;  // the process's peak resident set, KiB
  };
  const long before = peakKiB();
  CHECK_THROWS_WITH_AS(readPng(path), doctest::Contains("libpng could not read"), OutputError);
  CHECK_THROWS_WITH_AS(readPngText(contents(path)), doctest::Contains("unexpected end of data"), OutputError);
  CHECK(peakKiB() - before < 256 * 1024);
}

TEST_CASE("PNG bytes in memory that are not a whole PNG fail with libpng's message") {
  ScratchDir dir;
  const Image frame = Renderer(outputRenderOptions()).render(particles::test::fallingParticles().draw(), camera);
  writePng(dir / "frame.png", frame);
  const std::string bytes = contents(dir / "frame.png");
  CHECK_THROWS_WITH_AS(readPngText("GIF89a", "a.gif"), "a.gif is not a PNG file", OutputError);
  CHECK_THROWS_WITH_AS(readPngText(bytes.substr(0, 7)), "test.png is not a PNG file", OutputError);
  CHECK_THROWS_WITH_AS(readPngText(bytes.substr(0, bytes.size() / 2)),
                       doctest::Contains("libpng could not read test.png: unexpected end of data"), OutputError);
}

namespace {

// A particle's pixels and the background's in a frame of the falling particles at t = 0: the first
// particle (0.2, 0.6) is 6 px in radius, so its centre pixel is covered and a pixel 3 px in is too;
// the top-left corner is far from every shape.
struct Probe {
  Vec2 centre;
  Image frame;
};

Probe renderedFalling(bool transparent, Raster raster = Raster::triangles) {
  RenderOptions o = outputRenderOptions(transparent);
  o.raster = raster;
  System system = particles::test::fallingParticles();
  Renderer renderer(o);
  return {particles::test::projectToPixel(Vec2(0.2, 0.6), camera, o.width, o.height),
          renderer.render(system.draw(), camera)};
}

}  // namespace

TEST_CASE("a transparent background: alpha 0 where nothing is drawn, 255 on a particle, straight colour between") {
  const Palette colors = theme(ThemeName::dark);
  for (const Raster raster : {Raster::triangles, Raster::tiles, Raster::cpu}) {
    CAPTURE(int(raster));
    const Probe opaque = renderedFalling(false, raster);
    const Probe clear = renderedFalling(true, raster);
    const int cx = int(clear.centre.x()), cy = int(clear.centre.y());
    const std::uint8_t* inside = clear.frame.pixel(cx, cy);
    CHECK(int(inside[3]) == 255);
    CHECK(particles::test::sameRgb(inside, colors.particle));
    CHECK(int(clear.frame.pixel(cx + 3, cy)[3]) == 255);
    const std::uint8_t* corner = clear.frame.pixel(2, 2);
    CHECK(int(corner[3]) == 0);
    // Nothing drawn anywhere far from the shapes, and the opaque frame there is the theme's colour.
    CHECK(particles::test::sameRgb(opaque.frame.pixel(2, 2), colors.background));
    // Edge pixels: partial alpha, the particle's own colour (unpremultiplied, to rounding), and
    // composited over the theme's background they give the opaque frame's pixel.
    int edges = 0;
    for (int y = 0; y < clear.frame.height; ++y) {
      for (int x = 0; x < clear.frame.width; ++x) {
        const std::uint8_t* px = clear.frame.pixel(x, y);
        const std::uint8_t* over = opaque.frame.pixel(x, y);
        CHECK(int(over[3]) == 255);
        const int a = px[3];
        if (a == 0) {
          CHECK(particles::test::sameRgb(over, colors.background));
          continue;
        }
        if (a == 255) {
          CHECK(std::equal(px, px + 3, over));
          continue;
        }
        ++edges;
        const int particle[3] = {colors.particle.r, colors.particle.g, colors.particle.b};
        const int background[3] = {colors.background.r, colors.background.g, colors.background.b};
        for (int k = 0; k < 3; ++k) {
          // Straight colour is premultiplied ÷ alpha: an 8-bit premultiplied value is off by up to
          // half a level, so up to 128 / alpha levels after the division.
          CHECK(std::abs(int(px[k]) - particle[k]) <= 1 + 128 / a);
          const double composited = (px[k] * a + background[k] * (255 - a)) / 255.0;
          CHECK(std::abs(composited - over[k]) <= 2.0);
        }
      }
    }
    CHECK(edges > 20);  // three anti-aliased discs
  }
}

TEST_CASE("a transparent frame survives an RGBA PNG round trip, an opaque one is written as RGB") {
  ScratchDir dir;
  const Image clear = renderedFalling(true).frame;
  writePng(dir / "clear.png", clear, {.compressionLevel = 6, .alpha = true});
  CHECK(readPng(dir / "clear.png") == clear);
  writePng(dir / "dropped.png", clear, {.compressionLevel = 6});  // alpha dropped: read back as 255
  const Image dropped = readPng(dir / "dropped.png");
  CHECK(int(dropped.pixel(2, 2)[3]) == 255);
  // Byte 25 of a PNG is IHDR's colour type: 6 RGBA, 2 RGB.
  CHECK(int(contents(dir / "clear.png")[25]) == 6);
  CHECK(int(contents(dir / "dropped.png")[25]) == 2);
}

TEST_CASE("a GIF decodes with fps × duration frames, each close to its source, and one palette") {
  ScratchDir dir;
  setLibavVerbose(false);
  for (const auto& [fps, duration] : {std::pair{30, 1.0}, std::pair{25, 0.4}}) {
    CAPTURE(fps);
    const long frames = frameCount(duration, fps);
    const auto path = dir / ("out" + std::to_string(fps) + ".gif");
    const std::vector<Image> rendered = writeVideo(path, frames, fps, writerOptions(fps));
    const VideoInfo info = probeVideo(path, frames - 1);
    particles::test::checkVideo(info, "gif", 320, 180, frames);
    // Delays are whole centiseconds adding up to the video's length exactly.
    CHECK(info.durationSeconds == doctest::Approx(duration).epsilon(1e-9));
    // Three flat colours and their anti-aliased edges fit the 256 colours of the palette.
    checkLastFrame(info, rendered, 0.5);
  }
  CHECK(dir.entries() == std::set<std::string>{"out25.gif", "out30.gif"});
  // Delays under 2 cs are shown as 10 cs by browsers: more than 50 fps is refused before any file.
  CHECK_THROWS_AS(openFrameWriter(dir / "fast.gif", writerOptions(60)), std::invalid_argument);
  // An odd size is fine for a palette.
  FrameWriterOptions odd = writerOptions(10);
  odd.width = 321;
  auto writer = openFrameWriter(dir / "odd.gif", odd);
  writer->write(Image(321, 180));
  writer->finish();
  CHECK(probeVideo(dir / "odd.gif").width == 321);
  CHECK_FALSE(std::filesystem::exists(dir / "fast.gif"));
}

TEST_CASE("a WebM decodes as VP9 with fps × duration frames, with alpha, libvpx decodes its alpha plane") {
  ScratchDir dir;
  setLibavVerbose(false);
  const int fps = 30;
  const long frames = 12;
  const std::vector<Image> rendered = writeVideo(dir / "out.webm", frames, fps, writerOptions(fps));
  const VideoInfo info = probeVideo(dir / "out.webm", frames - 1);
  particles::test::checkVideo(info, "vp9", 320, 180, frames);
  CHECK(info.pixelFormat == "yuv420p");
  CHECK(info.alphaMode.empty());
  CHECK(info.durationSeconds == doctest::Approx(double(frames) / fps).epsilon(0.01));
  checkLastFrame(info, rendered, 2.0);

  FrameWriterOptions withAlpha = writerOptions(fps);
  withAlpha.alpha = true;
  const std::vector<Image> clearFrames = writeVideo(dir / "clear.webm", frames, fps, withAlpha, true);
  // libavcodec's own vp9 decoder sees the colour stream only; the track says there is alpha.
  const VideoInfo plain = probeVideo(dir / "clear.webm");
  CHECK(plain.alphaMode == "1");
  CHECK(plain.decodedPixelFormat == "yuv420p");
  const VideoInfo alpha = probeVideo(dir / "clear.webm", 0, "libvpx-vp9");
  CHECK(alpha.decodedPixelFormat == "yuva420p");
  CHECK(alpha.frames == frames);
  REQUIRE(alpha.sample.width == 320);
  // The first frame's particle is opaque and the corner transparent, to VP9's (lossy) precision;
  // the mean alpha error over the frame is small.
  const Vec2 c = particles::test::projectToPixel(Vec2(0.2, 0.6), camera, 320, 180);
  CHECK(int(alpha.sample.pixel(int(c.x()), int(c.y()))[3]) >= 250);
  CHECK(int(alpha.sample.pixel(2, 2)[3]) <= 5);
  double alphaError = 0;
  for (size_t i = 3; i < clearFrames.front().rgba.size(); i += 4) {
    alphaError += std::abs(int(alpha.sample.rgba[i]) - int(clearFrames.front().rgba[i]));
  }
  CHECK(alphaError / double(320 * 180) < 1.0);
  // Alpha is only for the outputs that keep it.
  for (const char* name : {"clear.mp4", "clear.gif"}) {
    CAPTURE(name);
    CHECK_THROWS_AS(openFrameWriter(dir / name, withAlpha), std::invalid_argument);
  }
  CHECK(dir.entries() == std::set<std::string>{"clear.webm", "out.webm"});
}

TEST_CASE("GIF and WebM replace an existing output only on success, and are the same bytes every time") {
  ScratchDir dir;
  setLibavVerbose(false);
  for (const char* name : {"out.gif", "out.webm"}) {
    CAPTURE(name);
    const auto path = dir / name;
    std::ofstream(path) << "previous run";
    {  // aborted, as the command line does on SIGINT
      auto writer = openFrameWriter(path, writerOptions(30));
      renderInto(*writer, 5, 30);
      writer->abort();
    }
    {  // dropped without finish(): an exception unwinding the frame loop
      auto writer = openFrameWriter(path, writerOptions(30));
      renderInto(*writer, 5, 30);
    }
    CHECK(contents(path) == "previous run");
    CHECK(dir.entries() == std::set<std::string>{name});
    auto first = openFrameWriter(path, writerOptions(30));
    renderInto(*first, 8, 30);
    first->finish();
    const std::string bytes = contents(path);
    CHECK(probeVideo(path).frames == 8);
    // The same frames again: the same file (libvpx with row-mt on this machine's threads, the
    // muxer's track ids fixed; the GIF's palette and encoding have no randomness).
    auto second = openFrameWriter(path, writerOptions(30));
    renderInto(*second, 8, 30);
    second->finish();
    CHECK(contents(path) == bytes);
    CHECK(dir.entries() == std::set<std::string>{name});
    std::filesystem::remove(path);
  }
}
