// Loads a scenario (the cloth by default), steps it for half a simulated second, prints a particle,
// its energy and the library's version, and saves the frame as a PNG when given a path: the
// smallest program built against an installed particles (CMakeLists.txt here; or
// `c++ -std=c++20 main.cpp $(pkg-config --cflags --libs particles)`).
//   cloth_example [SCENARIO [FRAME.png]]
#include <cstdio>
#include <string>

#include <particles/particles.hpp>

int main(int argc, char** argv) {
  const std::string path = argc > 1 ? argv[1] : "scenarios/cloth.yaml";
  try {
    particles::Scenario cloth = particles::Scenario::load(path);
    cloth.set("dt", 0.005);  // as `--set simulation.dt=0.005` or `--dt 0.005`
    particles::Simulation sim(cloth, 2);
    sim.advance(0.5);
    const int corner = sim.particleIndex(sim.particleNames().back());
    const particles::Point p = sim.position(corner);
    const particles::Energy e = sim.energy();
    std::printf("particles %s: '%s' at t = %.3f s after %ld steps of %s\n", particles::version(), cloth.name().c_str(),
                sim.time(), sim.steps(), std::string(particles::name(sim.integrator())).c_str());
    std::printf("%s at (%.17g, %.17g); energy %.6g J\n", sim.particleNames().back().c_str(), p.x, p.y, e.total);
    if (argc > 2) {
      particles::Renderer renderer({.width = 640, .height = 360});
      const particles::Image frame = renderer.render(sim);
      frame.savePng(argv[2]);
      std::printf("frame %dx%d saved to %s\n", frame.width, frame.height, argv[2]);
    }
    return 0;
  } catch (const particles::ScenarioError& e) {
    std::fprintf(stderr, "%s\n", e.what());  // FILE:LINE:COLUMN: error: KEY: why
    return 2;
  } catch (const particles::Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
}
