// Outputs (render/png_io.hpp, render/frame_writer.hpp): PNG round trip, H.264 MP4 decoded back
// through libavformat, PNG sequences, and what is left on disk when things go wrong.

#include <doctest/doctest.h>
#include <sys/resource.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <string>

#include "render/errors.hpp"
#include "render/frame_writer.hpp"
#include "render/png_io.hpp"
#include "render/png_sequence_writer.hpp"
#include "render/renderer.hpp"
#include "core/drawing.hpp"
#include "core/system.hpp"
#include "render/video_probe.hpp"
#include "render_support.hpp"
#include "core/solver.hpp"

using namespace particles;
using namespace particles::render;
using particles::test::ScratchDir;

namespace {

RenderOptions outputRenderOptions() {
  return particles::test::smallRenderOptions(320, 180);
}

const Camera camera{Vec2(0.1, -0.2), 2.4};

// Renders `count` frames of the falling particles at `fps` into the writer, as the command line
// will: frame i at t = i / fps.
std::vector<Image> renderInto(FrameWriter& writer, long count, int fps, bool keep = false) {
  System system = particles::test::fallingParticles();
  Solver solver(Integrator::Rk4);
  Renderer renderer(outputRenderOptions());
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

}  // namespace

TEST_CASE("frame counts and output kinds") {
  CHECK(frameCount(10.0, 60) == 600);
  CHECK(frameCount(0.5, 24) == 12);
  CHECK(frameCount(0.001, 30) == 1);
  CHECK(outputKind("a/b/out.mp4") == OutputKind::mp4);
  CHECK(outputKind("OUT.MP4") == OutputKind::mp4);
  CHECK(outputKind("frame.png") == OutputKind::png);
  CHECK(outputKind("frames/") == OutputKind::pngSequence);
  CHECK_THROWS_AS(outputKind("out.avi"), std::invalid_argument);
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
    auto writer = openFrameWriter(path, writerOptions(fps));
    const std::vector<Image> rendered = renderInto(*writer, frames, fps, true);
    CHECK(writer->framesWritten() == frames);
    writer->finish();

    const VideoInfo info = probeVideo(path, frames - 1);
    CHECK(info.codec == "h264");
    CHECK(info.pixelFormat == "yuv420p");
    CHECK(info.width == 320);
    CHECK(info.height == 180);
    CHECK(info.fps == doctest::Approx(fps));
    CHECK(info.frames == frames);
    CHECK(std::abs(info.durationSeconds - duration) <= 1.0 / fps);
    // The last decoded frame is the last rendered one (not the first, not blank): it differs from
    // its source only by compression and the YUV round trip.
    REQUIRE(info.sample.width == 320);
    const double error = meanAbsoluteDifference(info.sample, rendered.back());
    const double moved = meanAbsoluteDifference(rendered.front(), rendered.back());
    CHECK(error < 2.0);
    CHECK(error < moved / 4);
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
