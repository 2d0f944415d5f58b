// The public C++ API under careless use: references kept across set(), abort() racing finish()
// on another thread, a writer aborted before its first frame, advance() once per frame, a FIFO
// with no writer, fork(), huge values in messages, a report folder given with a trailing slash
// or checked into by several threads at once. The scripts/test stage under ASan + UBSan runs
// these too, where a use-after-free or a race on freed encoder state is a failure.
#include <doctest/doctest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <algorithm>
#include <csignal>
#include <fstream>
#include <mutex>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include <particles/particles.hpp>

#include "cli_support.hpp"
#include "source_tree.hpp"

using namespace particles::test;
namespace fs = std::filesystem;

namespace {

std::string carelessDemo(const std::string& name) {
  return (kScenarios / (name + ".yaml")).string();
}

particles::Image plainFrame(int width, int height, std::uint8_t red) {
  particles::Image image{width, height, std::vector<std::uint8_t>(size_t(width) * size_t(height) * 4, 255)};
  for (size_t i = 0; i < image.rgba.size(); i += 4) image.rgba[i] = red;
  return image;
}

// A manifest of one state check of a one-particle scenario: no frame, so no GL.
std::string oneStateManifest(const fs::path& dir) {
  std::ofstream(dir / "s.yaml") << "name: s\nparticles:\n  - {name: a, pos: [0, 0]}\nsimulation: {duration: 0.1}\n";
  std::ofstream(dir / "golden.yaml") << "states:\n  - {scenario: s.yaml, times: [0.1]}\n";
  return (dir / "golden.yaml").string();
}

std::vector<std::string> entriesOf(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

TEST_CASE("api careless: a scenario's name, description and file are copies that outlive set()") {
  particles::Scenario cloth = particles::Scenario::load(carelessDemo("cloth"));
  static_assert(std::is_same_v<decltype(cloth.name()), std::string>);
  static_assert(std::is_same_v<decltype(cloth.description()), std::string>);
  static_assert(std::is_same_v<decltype(cloth.file()), std::string>);
  const std::string name = cloth.name(), file = cloth.file();
  cloth.set("dt", 0.002).set("name", "renamed");
  CHECK(name == "cloth");
  CHECK(file == carelessDemo("cloth"));
  CHECK(cloth.name() == "renamed");
}

TEST_CASE("api careless: advance once per frame lands on the step render draws, whatever dt") {
  for (const double dt : {0.005, 0.007, 0.003}) {
    CAPTURE(dt);
    particles::Scenario cloth = particles::Scenario::load(carelessDemo("cloth"));
    cloth.set("dt", dt);
    particles::Simulation sim(cloth);
    particles::Simulation exact(cloth);
    for (int k = 1; k <= 90; ++k) {
      sim.advance(1.0 / 30);
      exact.advanceTo(k / 30.0);
      // render's frame k is at t = k / fps, on the last step at or before it (core/solver.hpp).
      const long expected = long(std::floor(k / 30.0 / dt + 1e-9));
      REQUIRE(sim.steps() == expected);
      REQUIRE(exact.steps() == expected);
    }
    CHECK(sim.time() == doctest::Approx(3.0).epsilon(dt / 3.0));
  }
  particles::Simulation sim(particles::Scenario::load(carelessDemo("cloth")));
  sim.step(10);
  sim.advance(0.005);  // the clock starts again where step() left it: half a step, no step
  CHECK(sim.steps() == 10);
  sim.advance(0.005);
  CHECK(sim.steps() == 11);
  CHECK_THROWS_AS(sim.advanceTo(0.05), particles::ArgumentError);  // behind t = 0.11
  CHECK_THROWS_AS(sim.advanceTo(std::nan("")), particles::ArgumentError);
  CHECK_NOTHROW(sim.advanceTo(0.11));  // where it is
  CHECK(sim.steps() == 11);
}

TEST_CASE("api careless: a writer aborted before its first frame writes nothing, ever") {
  Scratch scratch;
  const fs::path mp4 = scratch.dir / "never.mp4";
  particles::VideoWriter video(mp4.string());
  video.abort();
  CHECK_THROWS_WITH_AS(video.write(plainFrame(64, 48, 0)), doctest::Contains("aborted"), particles::ArgumentError);
  CHECK_THROWS_WITH_AS(video.finish(), doctest::Contains("aborted"), particles::ArgumentError);
  CHECK(entriesOf(scratch.dir).empty());
}

TEST_CASE("api careless: abort() on another thread while finish() encodes never frees the encoder under it") {
  Scratch scratch;
  for (int attempt = 0; attempt < 6; ++attempt) {
    CAPTURE(attempt);
    const fs::path mp4 = scratch.dir / ("race" + std::to_string(attempt) + ".mp4");
    particles::VideoWriter video(mp4.string(), {.fps = 30, .preset = "ultrafast"});
    for (int i = 0; i < 12; ++i) video.write(plainFrame(320, 240, std::uint8_t(i * 20)));
    std::string finished;
    std::thread finisher([&] {
      try {
        video.finish();
        finished = "done";
      } catch (const particles::ArgumentError& e) {
        finished = e.what();
      }
    });
    std::this_thread::sleep_for(std::chrono::milliseconds(2 * attempt));
    video.abort();
    finisher.join();
    if (finished == "done") {
      CHECK(fs::file_size(mp4) > 0);  // finish came first: the video is whole, abort did nothing
    } else {
      CHECK(finished.find("aborted") != std::string::npos);
      CHECK_FALSE(fs::exists(mp4));
    }
  }
  for (const std::string& name : entriesOf(scratch.dir)) CHECK(name.find(".partial") == std::string::npos);
}

TEST_CASE("api careless: a FIFO with no writer is refused at once, naming the file") {
  Scratch scratch;
  const fs::path fifo = scratch.dir / "scenario.yaml";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  try {
    particles::Scenario::load(fifo.string());
    FAIL("loaded");
  } catch (const particles::ScenarioError& e) {
    CHECK(e.file() == fifo.string());
    CHECK(std::string(e.what()).find("no writer") != std::string::npos);
  }
}

TEST_CASE("api careless: messages quote at most 80 bytes of a huge value, with its size") {
  const std::string huge(10 * 1024 * 1024, '1');
  particles::Scenario cloth = particles::Scenario::load(carelessDemo("cloth"));
  const auto shortWithSize = [&](const std::string& message) {
    CHECK(message.size() < 1000);
    CHECK(message.find("10485760 bytes") != std::string::npos);
  };
  try {
    cloth.set("dt", huge);
    FAIL("accepted");
  } catch (const particles::ScenarioError& e) {
    shortWithSize(e.what());
    CHECK(e.origin().size() < 300);
  }
  try {
    cloth.set(huge, "1");
    FAIL("accepted");
  } catch (const particles::ScenarioError& e) {
    shortWithSize(e.what());
  }
  particles::Simulation sim(cloth);
  try {
    sim.particleIndex(huge);
    FAIL("found");
  } catch (const particles::ArgumentError& e) {
    shortWithSize(e.what());
  }
}

TEST_CASE("api careless: a flow list of millions of items is refused before yaml-cpp holds it") {
  std::string text = "name: a\ndescription: [";
  for (int i = 0; i < 2'000'000; ++i) text += "1,";
  text += "1]\n";
  CHECK_THROWS_WITH_AS(particles::Scenario::fromText(text), doctest::Contains("--limit nodes=N"),
                       particles::ScenarioError);
  const std::string tooLarge(64 * 1024 * 1024 + 1, '#');
  CHECK_THROWS_WITH_AS(particles::Scenario::fromText(tooLarge), doctest::Contains("64 MiB"), particles::ScenarioError);
}

TEST_CASE("api careless: a simulation on two threads, stepped, then fork()ed: the child steps and ends") {
  particles::Simulation sim(particles::Scenario::load(carelessDemo("cloth")), 2);
  sim.advance(0.5);
  const pid_t child = ::fork();
  REQUIRE(child >= 0);
  if (child == 0) {
    int code = 0;
    try {
      sim.advance(0.5);  // on workers of the child's own
      code = sim.steps() == 100 ? 0 : 3;
      particles::Simulation moved = std::move(sim);
    } catch (...) {
      code = 4;
    }
    ::_exit(code);  // the pool was destroyed above, with `moved`: that is what used to wait forever
  }
  // A child still running after this long hangs: stopped, and the case fails.
  int status = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      FAIL("the forked child hung");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 0);
  sim.advance(0.5);  // the parent's workers are as they were
  CHECK(sim.steps() == 100);
}

TEST_CASE("api careless: a report folder given with a trailing slash is written, and replaced") {
  Scratch scratch;
  const std::string manifest = oneStateManifest(scratch.dir);
  const std::string folder = (scratch.dir / "report").string() + "/";
  const particles::golden::Report first = particles::golden::check(manifest, {.output = folder});
  CHECK(first.missing == 1);
  const particles::golden::Report second = particles::golden::check(manifest, {.output = folder + "/"});
  CHECK(second.missing == 1);
  CHECK(fs::exists(scratch.dir / "report" / "results.json"));
  CHECK(entriesOf(scratch.dir) == std::vector<std::string>{"golden.yaml", "report", "s.yaml"});
  for (const std::string bad : {"", ".", "..", "/"}) {
    CAPTURE(bad);
    CHECK_THROWS_AS(particles::golden::check(manifest, {.output = bad}), particles::ArgumentError);
  }
  // The folder that holds the manifest: an output that is one of the check's inputs.
  CHECK_THROWS_AS(particles::golden::check(manifest, {.output = scratch.dir.string()}), particles::ArgumentError);
}

TEST_CASE("api careless: checks into one report folder from several threads all succeed, leaving one report") {
  Scratch scratch;
  const std::string manifest = oneStateManifest(scratch.dir);
  std::vector<std::string> errors;
  std::mutex errorsMutex;
  std::vector<std::thread> threads;
  for (int i = 0; i < 9; ++i) {
    threads.emplace_back([&] {
      try {
        particles::golden::check(manifest, {.output = (scratch.dir / "report").string(), .jobs = 1});
      } catch (const particles::Error& e) {
        const std::lock_guard lock(errorsMutex);
        errors.push_back(e.what());
      }
    });
  }
  for (std::thread& t : threads) t.join();
  CHECK(errors.empty());
  for (const std::string& e : errors) MESSAGE(e);
  CHECK(entriesOf(scratch.dir) == std::vector<std::string>{"golden.yaml", "report", "s.yaml"});
  CHECK(fs::exists(scratch.dir / "report" / "results.json"));
}

TEST_CASE("api careless: an MP4 frame wider than x264 takes is an ArgumentError, before the encoder") {
  Scratch scratch;
  particles::VideoWriter video((scratch.dir / "wide.mp4").string());
  CHECK_THROWS_WITH_AS(video.write(plainFrame(16386, 2, 0)), doctest::Contains("at most 16384 px a side"),
                       particles::ArgumentError);
  CHECK(entriesOf(scratch.dir).empty());
}
