// `particles compare` end to end (docs/physics.md §10, §12; src/app/compare_command.hpp): exit codes 0 / 1
// / 2 / 3, what it prints, its options, and the --diff picture written whole or not at all. Runs
// the binary built next to this test on small PNGs written here.
#include <doctest/doctest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "render/image_compare.hpp"
#include "render/png_io.hpp"
#include "cli_support.hpp"
#include "render_support.hpp"

namespace fs = std::filesystem;
using RenderImage = particles::render::Image;  // not particles::Image, the public one
using particles::test::slurp;

using particles::test::contains;

namespace {

struct Run {
  int code = -1;
  std::string out, err;
};

// Runs `particles ARGS` in `dir`; stdout and stderr go to files outside it, so that the test can
// check that the command leaves nothing but its outputs behind.
Run runParticles(const particles::test::ScratchDir& dir, const std::string& args) {
  const fs::path exe = fs::read_symlink("/proc/self/exe").parent_path() / "particles";
  REQUIRE_MESSAGE(fs::exists(exe), "the particles program is not built next to the tests: " << exe);
  const fs::path out = dir.path().string() + ".stdout", err = dir.path().string() + ".stderr";
  const std::string command = "cd '" + dir.path().string() + "' && '" + exe.string() + "' " + args + " > '" +
                              out.string() + "' 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  Run r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

RenderImage grey(int w, int h, std::uint8_t level) {
  RenderImage img(w, h);
  for (size_t i = 0; i < img.rgba.size(); ++i) img.rgba[i] = (i % 4 == 3) ? 255 : level;
  return img;
}


// expected.png: 10×10 grey; actual.png: the same with 3 pixels changed (3 % of the pixels, the
// largest by 200, inside x 2…7, y 1…3).
struct Pair {
  particles::test::ScratchDir dir;
  Pair() {
    const RenderImage expected = grey(10, 10, 50);
    RenderImage actual = expected;
    actual.pixel(2, 3)[0] = 250;
    actual.pixel(7, 1)[1] = 0;
    actual.pixel(4, 2)[2] = 90;
    particles::render::writePng(dir / "expected.png", expected);
    particles::render::writePng(dir / "actual.png", actual);
  }
};

}  // namespace

TEST_CASE("compare cli: identical frames match (exit 0) and the report says so") {
  Pair p;
  const Run r = runParticles(p.dir, "compare expected.png expected.png");
  CHECK(r.code == 0);
  CHECK(r.err.empty());
  CHECK(contains(r.out, "share:"));
  CHECK(contains(r.out, "0.0000 %"));
  CHECK(contains(r.out, "largest: 0"));
  CHECK(contains(r.out, "box:     none"));
  CHECK(contains(r.out, "ok"));
  CHECK(runParticles(p.dir, "compare expected.png expected.png --quiet").out.empty());
}

TEST_CASE("compare cli: different frames fail with exit 1 and print share, largest difference and box") {
  Pair p;
  const Run r = runParticles(p.dir, "compare expected.png actual.png");
  CHECK(r.code == 1);
  CHECK(contains(r.out, "3.0000 %"));
  CHECK(contains(r.out, "3 of 100"));
  CHECK(contains(r.out, "by more than 16"));  // the default threshold
  CHECK(contains(r.out, "bound 0.02 %"));     // the default bound
  CHECK(contains(r.out, "largest: 200"));
  CHECK(contains(r.out, "x 2…7, y 1…3"));
  CHECK(contains(r.out, "6×3 px"));
  CHECK(contains(r.out, "DIFFERENT"));
  // --quiet still reports a failure.
  const Run q = runParticles(p.dir, "compare expected.png actual.png -q");
  CHECK(q.code == 1);
  CHECK(contains(q.out, "largest: 200"));
}

TEST_CASE("compare cli: --threshold and --max-share set the tolerance") {
  Pair p;
  CHECK(runParticles(p.dir, "compare expected.png actual.png --max-share 0.03").code == 0);  // 3 % ≤ 3 %
  CHECK(runParticles(p.dir, "compare expected.png actual.png --max-share 0.029").code == 1);
  CHECK(runParticles(p.dir, "compare expected.png actual.png --threshold 200").code == 0);  // none above 200
  const Run r = runParticles(p.dir, "compare expected.png actual.png --threshold 40");      // the 40 drops out
  CHECK(r.code == 1);
  CHECK(contains(r.out, "2 of 100"));
  CHECK(contains(r.out, "x 2…7, y 1…3"));
  CHECK(contains(r.out, "largest: 200"));
}

TEST_CASE("compare cli: bad input exits with 2 and says what is wrong") {
  Pair p;
  particles::render::writePng(p.dir / "big.png", grey(12, 8, 50));
  Run r = runParticles(p.dir, "compare expected.png big.png --diff d.png");
  CHECK(r.code == 2);
  CHECK(contains(r.err, "expected.png"));
  CHECK(contains(r.err, "big.png"));
  CHECK(contains(r.err, "10×10 expected"));
  CHECK(contains(r.err, "12×8 actual"));
  CHECK_FALSE(fs::exists(p.dir / "d.png"));

  r = runParticles(p.dir, "compare expected.png missing.png");
  CHECK(r.code == 2);
  CHECK(contains(r.err, "missing.png"));

  std::ofstream(p.dir / "text.png") << "not a png at all";
  r = runParticles(p.dir, "compare text.png expected.png");
  CHECK(r.code == 2);
  CHECK(contains(r.err, "text.png"));

  CHECK(runParticles(p.dir, "compare expected.png").code == 2);
  CHECK(runParticles(p.dir, "compare expected.png actual.png --threshold 256").code == 2);
  CHECK(runParticles(p.dir, "compare expected.png actual.png --threshold -1").code == 2);
  CHECK(runParticles(p.dir, "compare expected.png actual.png --max-share 1.5").code == 2);
  CHECK(runParticles(p.dir, "compare expected.png actual.png --max-share x").code == 2);
}

TEST_CASE("compare cli: --diff writes the diff picture, whole or not at all (exit 3)") {
  Pair p;
  Run r = runParticles(p.dir, "compare expected.png actual.png --diff d.png");
  CHECK(r.code == 1);  // the comparison's verdict, not the diff's
  CHECK(contains(r.out, "d.png"));
  REQUIRE(fs::exists(p.dir / "d.png"));
  const RenderImage diff = particles::render::readPng(p.dir / "d.png");
  CHECK(diff == particles::render::diffImage(particles::render::readPng(p.dir / "expected.png"),
                                             particles::render::readPng(p.dir / "actual.png")));
  CHECK(p.dir.entries() == std::set<std::string>{"actual.png", "d.png", "expected.png"});  // no temporaries

  // Written when the frames match too; replaced whole.
  r = runParticles(p.dir, "compare expected.png expected.png --diff d.png");
  CHECK(r.code == 0);
  CHECK(particles::render::readPng(p.dir / "d.png") ==
        particles::render::diffImage(particles::render::readPng(p.dir / "expected.png"),
                                     particles::render::readPng(p.dir / "expected.png")));

  // An impossible destination: exit 3, and nothing is left behind.
  r = runParticles(p.dir, "compare expected.png actual.png --diff no/such/dir/d.png");
  CHECK(r.code == 3);
  CHECK(contains(r.err, "--diff"));
  CHECK(contains(r.err, "no/such/dir/d.png"));
  fs::create_directory(p.dir / "adir.png");
  r = runParticles(p.dir, "compare expected.png actual.png --diff adir.png");
  CHECK(r.code == 3);
  CHECK(p.dir.entries() == std::set<std::string>{"actual.png", "adir.png", "d.png", "expected.png"});
  CHECK(fs::is_empty(p.dir / "adir.png"));
}

TEST_CASE("compare cli: --help documents the exit codes and the defaults") {
  Pair p;
  const Run r = runParticles(p.dir, "compare --help");
  CHECK(r.code == 0);
  CHECK(contains(r.out, "--diff"));
  CHECK(contains(r.out, "--threshold"));
  CHECK(contains(r.out, "--max-share"));
  CHECK(contains(r.out, "16"));
  CHECK(contains(r.out, "0.0002"));
  CHECK(contains(r.out, "1 they differ"));
  CHECK(contains(r.out, "golden/README.md"));
}
