// The GL backends (render/gl_backend.hpp): every backend this build has draws the same bytes,
// renderers of both take turns in one thread, what auto picks, the requests a build refuses; and on
// the command line --gl, PARTICLES_GL, --gpu and --version.
#include <doctest/doctest.h>

#include <cstdlib>
#include <filesystem>
#include <optional>
#include <regex>
#include <string>
#include <utility>
#include <vector>

#include "cli_support.hpp"
#include "core/solver.hpp"
#include "render/errors.hpp"
#include "render/gl_backend.hpp"
#include "render/image_compare.hpp"
#include "render/renderer.hpp"
#include "render_support.hpp"
#include "scenario/scenario.hpp"
#include "skip.hpp"
#include "support/library_names.hpp"

namespace fs = std::filesystem;
using namespace particles;
using namespace particles::render;
using particles::test::DemoFrame;
using particles::test::demoFrame;

using particles::test::contains;

namespace {

std::vector<GlBackend> builtBackends() {
  std::vector<GlBackend> built;
  for (GlBackend b : {GlBackend::egl, GlBackend::osmesa}) {
    if (glBackendBuilt(b)) built.push_back(b);
  }
  return built;
}


// The message of what `f` throws as E, "" when it throws nothing.
template <class E, class F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

// Every sample count (particles::test::sampleCountsToCompare), opaque and with a transparent
// background.
std::vector<std::pair<int, bool>> sampleCountsOpaqueAndTransparent() {
  std::vector<std::pair<int, bool>> cases;
  for (int msaa : particles::test::sampleCountsToCompare()) {
    for (bool transparent : {false, true}) cases.emplace_back(msaa, transparent);
  }
  return cases;
}

}  // namespace

TEST_CASE("GL backends: every backend built draws the demos' frames to the same bytes") {
  const std::vector<GlBackend> backends = builtBackends();
  REQUIRE(!backends.empty());
  if (backends.size() == 1) MESSAGE("only " << glBuildDescription() << ": nothing to compare it with");
  // cloth_t2.5 has the cursor's tip and the rail on pixel centres whose pixels differed when EGL
  // drew upright (render/egl_context.cpp); the other two, contacts with colliders.
  const std::pair<const char*, double> demos[] = {{"cloth", 2.5}, {"soft_body", 31.5}, {"rigid_chain", 0.65}};
  for (const auto& [name, at] : demos) {
    const DemoFrame frame = demoFrame(name, at);
    for (const auto& [width, height] : {std::pair{320, 240}, std::pair{333, 217}}) {  // odd sizes too
      // With a transparent background too: alpha kept by both framebuffers, colour premultiplied alike.
      for (const auto& [msaa, transparent] : sampleCountsOpaqueAndTransparent()) {
        CAPTURE(std::string(name));
        CAPTURE(width);
        CAPTURE(height);
        CAPTURE(msaa);
        CAPTURE(transparent);
        RenderOptions options;
        options.width = width;
        options.height = height;
        options.msaa = msaa;
        options.transparentBackground = transparent;
        options.raster = Raster::resident;  // drawn by GL (without a GPU, auto draws on the CPU)
        std::optional<Image> first;
        for (GlBackend backend : backends) {
          CAPTURE(glBackendName(backend));
          Renderer renderer(options, {backend});
          CHECK(renderer.gl().backend == backend);
          const Image& image = renderer.render(frame.drawing, frame.camera);
          if (!first) {
            first = image;
          } else if (image != *first) {
            // Mesa 25.0's framebuffer objects (EGL) decide a sample lying exactly on an edge
            // otherwise than its OSMesa buffer, which draws as both backends of Mesa 22.3 do (the
            // same bytes): the cloth at 320×240 has its rail's lower edge on the pixel centres of row
            // 19, whose pixels differ at 1 sample (168, by up to 180) and 16 (170, by up to 11), and
            // no other frame or pixel does. So: the same bytes but for one row.
            const ImageComparison c = compareImages(*first, image, {0, 1.0});
            REQUIRE(c.box);
            CHECK_MESSAGE(c.box->height() == 1, c.differing << " pixels differ, by up to " << c.largestDifference);
          }
        }
      }
    }
  }
}

TEST_CASE("GL backends: frames read back ahead (two pixel-pack buffers) are the frames render draws, in order") {
  // EGL asked to read ahead (as it does on a GPU): two frames submitted, then collected oldest
  // first; OSMesa, which draws into the image itself, reads each at once, as EGL does on llvmpipe
  // by default. Each gives render's bytes, opaque and transparent.
  const DemoFrame early = demoFrame("cloth", 1.0), late = demoFrame("cloth", 3.0);
  for (GlBackend backend : builtBackends()) {
    for (bool transparent : {false, true}) {
      CAPTURE(glBackendName(backend));
      CAPTURE(transparent);
      RenderOptions o = particles::test::smallRenderOptions();
      o.transparentBackground = transparent;
      o.raster = Raster::resident;  // a GL path (without a GPU, auto draws on the CPU: tests/test_render_cpu.cpp)
      GlRequest request{backend};
      request.readBack = GlRequest::ReadBack::ahead;
      Renderer renderer(o, request);
      CHECK(!Renderer(o, GlRequest{backend}).readsAhead());  // llvmpipe's default
      const Image first = renderer.render(early.byIndex, early.camera);
      const Image second = renderer.render(late.byIndex, late.camera);
      CHECK(first.rgba != second.rgba);
      CHECK(renderer.readsAhead() == (backend == GlBackend::egl));
      if (!renderer.readsAhead()) continue;
      renderer.submit(early.byIndex, early.camera);
      renderer.submit(late.byIndex, late.camera);
      CHECK(renderer.collect().rgba == first.rgba);
      renderer.submit(early.byIndex, early.camera);  // a buffer is free again
      CHECK(renderer.collect().rgba == second.rgba);
      CHECK(renderer.collect().rgba == first.rgba);
    }
  }
}

TEST_CASE("GL backends: renderers of both take turns in one thread, each drawing in its own buffer") {
  if (builtBackends().size() < 2)
    return particles::test::skipTest("needs both backends, this build has " + glBuildDescription());
  const System system = particles::test::fallingParticles();
  const Drawing a = system.draw();
  Drawing b = a;
  b.particles[0] += Vec2(0.3, 0);
  const Camera camera{Vec2(0.1, 0), 2.4};
  RenderOptions options = particles::test::smallRenderOptions();
  options.raster = Raster::triangles;  // drawn by GL (without a GPU, auto draws on the CPU)
  const Image expectedA = Renderer(options, {GlBackend::osmesa}).render(a, camera);
  const Image expectedB = Renderer(options, {GlBackend::osmesa}).render(b, camera);
  REQUIRE(expectedA != expectedB);

  Renderer egl(options, {GlBackend::egl});
  Renderer osmesa(options, {GlBackend::osmesa});
  // OSMesa's context is current now, and EGL still believes its own is: each must bind its own.
  CHECK(egl.render(a, camera) == expectedA);
  CHECK(osmesa.render(b, camera) == expectedB);
  CHECK(egl.render(b, camera) == expectedB);
  CHECK(osmesa.render(a, camera) == expectedA);
  {
    Renderer secondEgl(options, {GlBackend::egl});  // the same EGL display, destroyed first
    CHECK(secondEgl.render(b, camera) == expectedB);
  }
  CHECK(egl.render(a, camera) == expectedA);  // the display outlives the context that went
}

TEST_CASE("GL backends: auto draws with EGL's software device, llvmpipe, and says so") {
  RenderOptions options = particles::test::smallRenderOptions();
  options.raster = Raster::resident;  // a GL path: the cpu path makes no context
  Renderer renderer(options);
  const GlInfo& info = renderer.gl();
  CAPTURE(describe(info));
  CHECK(info.renderer.starts_with("llvmpipe"));
  CHECK(!info.version.empty());
  if (glBackendBuilt(GlBackend::egl)) {
    CHECK(info.backend == GlBackend::egl);
    CHECK(info.device == "software device");
    CHECK(info.fallback.empty());
    CHECK(describe(info).starts_with("egl, software device: llvmpipe"));
  } else {
    CHECK(info.backend == GlBackend::osmesa);
  }
  const GlInfo probed = probeGl({});
  CHECK(probed.backend == info.backend);
  CHECK(probed.renderer == info.renderer);
}

TEST_CASE("GL backends: names, the backends of this build and the requests it refuses") {
  for (GlBackend b : {GlBackend::automatic, GlBackend::egl, GlBackend::osmesa}) {
    CHECK(glBackendFromName(glBackendName(b)) == b);
  }
  CHECK(glBackendNames() == std::vector<std::string>{"auto", "egl", "osmesa"});
  CHECK_FALSE(glBackendFromName("EGL"));
  CHECK_FALSE(glBackendFromName(""));
  CHECK(glBackendBuilt(GlBackend::automatic));
  CHECK((glBackendBuilt(GlBackend::egl) || glBackendBuilt(GlBackend::osmesa)));
  // OSMesa with a GPU: refused for the GPU, or for OSMesa where the build has none.
  const std::string gpuWithOsMesa = thrownMessage<std::invalid_argument>([] { validate({GlBackend::osmesa, true}); });
  CHECK_MESSAGE(
      contains(gpuWithOsMesa, glBackendBuilt(GlBackend::osmesa) ? "a GPU needs EGL: OSMesa draws on the CPU only"
                                                                : "this particles has no OSMesa backend"),
      gpuWithOsMesa);
  for (GlBackend b : {GlBackend::egl, GlBackend::osmesa}) {
    if (glBackendBuilt(b)) continue;
    const std::string message =
        thrownMessage<std::invalid_argument>([&] { Renderer renderer(particles::test::smallRenderOptions(), {b}); });
    CHECK_MESSAGE(contains(message, "-DPARTICLES_WITH_"), message);
  }
}

TEST_CASE("GL backends: a request's threads become llvmpipe's LP_NUM_THREADS, unless the user set it") {
  // Mesa reads the variable when it makes a context; the request sets it first. 1 thread is
  // llvmpipe's 0 (rasterise on the calling thread). The variable is put back afterwards, so that
  // later tests draw with the machine's default.
  const char* before = std::getenv("LP_NUM_THREADS");
  const std::optional<std::string> saved = before ? std::optional<std::string>(before) : std::nullopt;
  auto lpThreadsAfter = [](int threads) {
    probeGl({.threads = threads});
    const char* value = std::getenv("LP_NUM_THREADS");
    return value ? std::string(value) : std::string("(unset)");
  };
  unsetenv("LP_NUM_THREADS");
  CHECK(lpThreadsAfter(0) == "(unset)");
  CHECK(lpThreadsAfter(1) == "0");
  unsetenv("LP_NUM_THREADS");
  CHECK(lpThreadsAfter(3) == "3");
  setenv("LP_NUM_THREADS", "5", 1);
  CHECK(lpThreadsAfter(2) == "5");
  CHECK_THROWS_AS(validate(GlRequest{.threads = -1}), std::invalid_argument);
  if (saved) {
    setenv("LP_NUM_THREADS", saved->c_str(), 1);
  } else {
    unsetenv("LP_NUM_THREADS");
  }
}

TEST_CASE("GL backends: a GPU request draws on hardware, or fails saying there is none") {
  if (!glBackendBuilt(GlBackend::egl))
    return particles::test::skipTest("needs EGL, this build has " + glBuildDescription());
  for (GlBackend backend : {GlBackend::egl, GlBackend::automatic}) {
    try {
      Renderer renderer(particles::test::smallRenderOptions(), {backend, true});
      MESSAGE("a GPU is here: " << describe(renderer.gl()));
      CHECK(renderer.gl().device.starts_with("hardware device"));
    } catch (const RenderError& e) {
      CHECK_MESSAGE(contains(e.what(), "a GPU was asked for, but EGL lists no hardware device"), e.what());
    }
  }
}

// --- the command line ---------------------------------------------------------------------------

using particles::test::lines;
using particles::test::loaderStarted;
using particles::test::Result;
using particles::test::Scratch;
using particles::test::slurp;

TEST_CASE("cli render --gl: each backend draws the same PNG, and the option wins over PARTICLES_GL") {
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  std::optional<std::string> first;
  for (GlBackend backend : builtBackends()) {
    const std::string name(glBackendName(backend));
    // PARTICLES_GL names the other backend, or nonsense: --gl decides.
    const Result r =
        s.run("render s.yaml -o " + name + ".png --at 0.5 --verbose --raster resident --gl " + name, "PARTICLES_GL=nonsense");
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "GL: " + name + ", "), r.err);
    const std::string png = slurp(s.dir / (name + ".png"));
    if (!first) {
      first = png;
    } else {
      CHECK(png == *first);
    }
  }
  // Without --gl, PARTICLES_GL decides; empty is unset, and unset is auto.
  for (GlBackend backend : builtBackends()) {
    const std::string name(glBackendName(backend));
    const Result r = s.run("render s.yaml -o env.png --at 0.5 --verbose --raster resident", "PARTICLES_GL=" + name);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "GL: " + name + ", "), r.err);
  }
  const std::string autoName = glBackendBuilt(GlBackend::egl) ? "egl" : "osmesa";
  for (const char* environment : {"-u PARTICLES_GL", "PARTICLES_GL=", "PARTICLES_GL=auto"}) {
    CAPTURE(environment);
    const Result r = s.run("render s.yaml -o auto.png --at 0.5 --verbose --raster resident", environment);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "GL: " + autoName + ", "), r.err);
  }
  // The cpu path (auto's without a GPU) makes no GL context, whatever names one.
  std::vector<std::string> environments = {"-u PARTICLES_GL"};
  for (GlBackend backend : builtBackends()) environments.push_back("PARTICLES_GL=" + std::string(glBackendName(backend)));
  for (const std::string& environment : environments) {
    CAPTURE(environment);
    const Result r = s.run("render s.yaml -o cpu.png --at 0.5 --verbose", environment);
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "GL: none (the cpu raster)\nraster: cpu"), r.err);
  }
}

TEST_CASE("cli render --gl, PARTICLES_GL: unknown names and missing backends are usage errors, exit 2") {
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  Result r = s.run("render s.yaml -o a.png --at 0.5", "PARTICLES_GL=vulkan");
  CHECK(r.code == 2);
  CHECK_MESSAGE(contains(r.err, "error: PARTICLES_GL=vulkan: expected auto, egl, osmesa"), r.err);
  r = s.run("render s.yaml -o a.png --at 0.5 --gl vulkan");
  CHECK(r.code == 2);
  CHECK_MESSAGE(contains(r.err, "--gl"), r.err);
  r = s.run("render s.yaml -o a.png --at 0.5 --gl osmesa --gpu");
  CHECK(r.code == 2);
  CHECK_MESSAGE(r.err.starts_with("error: --gl osmesa with --gpu: "), r.err);
  if (glBackendBuilt(GlBackend::osmesa)) CHECK_MESSAGE(contains(r.err, "a GPU needs EGL"), r.err);
  for (GlBackend backend : {GlBackend::egl, GlBackend::osmesa}) {
    if (glBackendBuilt(backend)) continue;
    const std::string name(glBackendName(backend));
    r = s.run("render s.yaml -o a.png --at 0.5 --gl " + name);
    CHECK(r.code == 2);
    CHECK_MESSAGE(contains(r.err, "error: --gl " + name + ": this particles has no"), r.err);
    CHECK_MESSAGE(contains(r.err, "-DPARTICLES_WITH_"), r.err);
    r = s.run("render s.yaml -o a.png --at 0.5", "PARTICLES_GL=" + name);
    CHECK(r.code == 2);
    CHECK_MESSAGE(contains(r.err, "error: PARTICLES_GL=" + name + ": this particles has no"), r.err);
  }
  CHECK(s.files() == std::vector<std::string>{"s.yaml"});
}

TEST_CASE("cli render --gpu: without a GPU, a clear error, exit 3 and no output") {
  if (!glBackendBuilt(GlBackend::egl))
    return particles::test::skipTest("needs EGL, this build has " + glBuildDescription());
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  for (const char* output : {"g.png --at 0.5", "g.mp4", "frames/"}) {
    CAPTURE(output);
    const Result r = s.run(std::string("render s.yaml --quiet --verbose --gpu -o ") + output, "-u PARTICLES_GL");
    if (r.code == 0) {
      MESSAGE("a GPU is here: " << r.err);
      CHECK(contains(r.err, "GL: egl, hardware device"));
      continue;
    }
    CHECK(r.code == 3);
    CHECK_MESSAGE(r.err.starts_with("error: a GPU was asked for, but EGL lists no hardware device"), r.err);
    CHECK(s.files() == std::vector<std::string>{"s.yaml"});
  }
}

// Mesa's driver, LLVM and OSMesa are in the loader's account of a run (loaderStarted) only when a
// GL context is made.
TEST_CASE("cli render: the cpu path loads no GL driver, LLVM or OSMesa, and a GL path loads its own") {
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  Result r = s.run("render s.yaml -o cpu.png --at 0.5 --quiet", "-u PARTICLES_GL LD_DEBUG=libs");
  REQUIRE(r.code == 0);
  CHECK_MESSAGE(loaderStarted(r.err, "libc.so"), r.err);  // the log is there
  for (const char* library : {"libOSMesa", "libLLVM", "_dri.so"}) {
    CAPTURE(library);
    CHECK(!loaderStarted(r.err, library));
  }
  if (glBackendBuilt(GlBackend::osmesa)) {
    r = s.run("render s.yaml -o osmesa.png --at 0.5 --quiet --raster resident --gl osmesa", "LD_DEBUG=libs");
    REQUIRE(r.code == 0);
    CHECK(loaderStarted(r.err, "libOSMesa"));
    // A library that cannot be opened (here an empty file found first) is an error naming it, exit
    // 3 and no output; the cpu path does not notice.
    const std::string soname(particles::test::osmesaSoname());
    REQUIRE(!soname.empty());
    fs::create_directory(s.dir / "lib");
    s.write("lib/" + soname, "");
    r = s.run("render s.yaml -o broken.png --at 0.5 --raster resident --gl osmesa", "LD_LIBRARY_PATH=lib");
    CHECK(r.code == 3);
    CHECK_MESSAGE(r.err.starts_with("error: OSMesa's library " + soname + " could not be loaded ("), r.err);
    CHECK(!fs::exists(s.dir / "broken.png"));
    r = s.run("render s.yaml -o cpu2.png --at 0.5", "LD_LIBRARY_PATH=lib PARTICLES_GL=osmesa");
    CHECK_MESSAGE(r.code == 0, r.err);
  }
  if (glBackendBuilt(GlBackend::egl)) {
    r = s.run("render s.yaml -o egl.png --at 0.5 --quiet --raster resident --gl egl", "LD_DEBUG=libs");
    REQUIRE(r.code == 0);
    CHECK(!loaderStarted(r.err, "libOSMesa"));  // OSMesa is opened only for its own contexts
  }
}

TEST_CASE("cli render: EGL that cannot start fails --gl egl with exit 3, and auto falls back to OSMesa") {
  if (!glBackendBuilt(GlBackend::egl))
    return particles::test::skipTest("needs EGL, this build has " + glBuildDescription());
  Scratch s;
  s.write("s.yaml", particles::test::kSwingScenario);
  // GLVND's libEGL finds no vendor library (Mesa's) to load: EGL offers no platform at all.
  const std::string noEgl = "-u PARTICLES_GL __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json";
  Result r = s.run("render s.yaml -o egl.png --at 0.5 --gl egl --raster resident", noEgl);
  CHECK(r.code == 3);
  CHECK_MESSAGE(r.err.starts_with("error: EGL lists no devices"), r.err);
  CHECK(s.files() == std::vector<std::string>{"s.yaml"});
  // The cpu path needs no GL, so it draws where EGL cannot start, --gl egl or not.
  r = s.run("render s.yaml -o cpu.png --at 0.5 --gl egl --verbose", noEgl);
  REQUIRE_MESSAGE(r.code == 0, r.err);
  CHECK_MESSAGE(contains(r.err, "GL: none (the cpu raster)"), r.err);
  CHECK(fs::exists(s.dir / "cpu.png"));
  r = s.run("render s.yaml -o auto.png --at 0.5 --verbose --raster resident", noEgl);
  if (glBackendBuilt(GlBackend::osmesa)) {
    REQUIRE_MESSAGE(r.code == 0, r.err);
    CHECK_MESSAGE(contains(r.err, "GL: osmesa, off-screen buffer: llvmpipe"), r.err);
    CHECK_MESSAGE(contains(r.err, "(EGL: EGL lists no devices"), r.err);
  } else {
    CHECK(r.code == 3);
  }
}

TEST_CASE("cli --version: the program's version, then the GL backend and renderer render would use") {
  Scratch s;
  Result r = s.run("--version", "-u PARTICLES_GL");
  REQUIRE(r.code == 0);
  std::vector<std::string> out = lines(r.out);
  REQUIRE_MESSAGE(out.size() == 2, r.out);
  CHECK_MESSAGE(std::regex_match(out[0], std::regex(R"(particles \d+\.\d+\.\d+ build [0-9a-f]{16})")), out[0]);
  const std::string autoName = glBackendBuilt(GlBackend::egl) ? "egl" : "osmesa";
  CHECK_MESSAGE(out[1].starts_with("GL: " + autoName + ", "), out[1]);
  CHECK_MESSAGE(std::regex_search(out[1], std::regex(R"(: llvmpipe \(LLVM .*\), OpenGL \d+\.\d+)")), out[1]);

  for (GlBackend backend : builtBackends()) {
    const std::string name(glBackendName(backend));
    r = s.run("--version", "PARTICLES_GL=" + name);
    REQUIRE(r.code == 0);
    out = lines(r.out);
    REQUIRE(out.size() == 2);
    CHECK_MESSAGE(out[1].starts_with("GL (PARTICLES_GL=" + name + "): " + name + ", "), out[1]);
  }
  // No GL to be had is said, not failed.
  r = s.run("--version", "PARTICLES_GL=nonsense");
  CHECK(r.code == 0);
  CHECK_MESSAGE(contains(r.out, "\nGL (PARTICLES_GL=nonsense): none available: PARTICLES_GL=nonsense: expected auto"),
                r.out);
  if (glBackendBuilt(GlBackend::egl)) {
    r = s.run("--version", "PARTICLES_GL=egl __EGL_VENDOR_LIBRARY_FILENAMES=/nonexistent/egl_vendor.json");
    CHECK(r.code == 0);
    CHECK_MESSAGE(contains(r.out, "\nGL (PARTICLES_GL=egl): none available: EGL lists no devices"), r.out);
  }
}
