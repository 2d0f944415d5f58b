#pragma once
// Scenario files (docs/physics.md §11): YAML in, a built System plus the simulation and render settings out.
// Every key, type, unit, default and range is documented in docs/scenarios.md.
//
// Bad input never crashes and never half-builds: the loader throws ScenarioError naming the file,
// the line and column (1-based) and the key path (`forces[2].ks`), and saying what was expected.

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/drawing.hpp"
#include "core/integrators.hpp"
#include "core/system.hpp"
#include "input/text_file.hpp"
#include "scenario/scenario_error.hpp"
#include "style/style.hpp"
#include "style/view.hpp"

namespace particles::scenario {

// Limits the loader enforces beyond each key's own range (docs/scenarios.md, `particles schema`).
inline constexpr long kMaxSteps = 1'000'000'000;  // a run longer than this is a typo, not a plan
inline constexpr long long kMaxGridSide = 10'000;
inline constexpr double kMinFps = 1e-3, kMaxFps = particles::kMaxFps;  // render.fps

// How large a scene may be, counted from the file before anything is built (so a few hundred bytes
// that name a grid two hundred times, or repeat an entry through YAML aliases, cost nothing before
// they are refused). The defaults leave room for a 1000 × 1000 cloth with every spring family;
// `--limit NAME=N` raises one for scenes that are meant to be larger (docs/scenarios.md, "Limits").
struct SceneLimits {
  long long particles = 1'000'000;     // particles, grid particles and rigid bodies
  long long springs = 8'000'000;       // grid springs and the forces section's springs and forces
  long long constraints = 1'000'000;   // the constraints section's constraints
  long long endpoints = 16'000'000;    // points the references name, whole grids and lists expanded
  long long entries = 1'000'000;       // entries of the kind sections, YAML aliases expanded
  // Values, keys and lists in the file (YAML nodes), counted before yaml-cpp builds them, which
  // costs hundreds of bytes each: 250,000 keep a scenario's tree within about 200 MiB (bench/
  // README.md, "Measurements behind choices in the source"). A large system is a grid, a few nodes
  // for any number of points.
  long long nodes = 250'000;
};
// The largest value `--limit` accepts: particle indices are ints.
inline constexpr long long kMaxSceneLimit = 1'000'000'000;
// The names `--limit` knows, each with the member it sets.
struct SceneLimitName {
  std::string_view name;
  long long SceneLimits::*member;
};
inline constexpr SceneLimitName kSceneLimitNames[] = {{"particles", &SceneLimits::particles},
                                                      {"springs", &SceneLimits::springs},
                                                      {"constraints", &SceneLimits::constraints},
                                                      {"endpoints", &SceneLimits::endpoints},
                                                      {"entries", &SceneLimits::entries},
                                                      {"nodes", &SceneLimits::nodes}};
// Sets one limit from `NAME=N` as given to --limit; throws ScenarioError naming the option when
// the name is unknown or N is not a whole number from 1 to kMaxSceneLimit.
void applyLimitOption(SceneLimits& limits, std::string_view text);

struct SimulationSettings {
  Integrator integrator = Integrator::rk4;
  double dt = 0.01;        // s, > 0
  double duration = 10.0;  // simulated seconds, > 0
  // The implicit integrators' linear solve (core/implicit_solver.hpp); set on the System too.
  ImplicitSolver implicitSolver = ImplicitSolver::automatic;
  // Steps of dt that cover the duration (the last one may end up to dt − ε past it).
  long steps() const;
};

struct RenderSettings {
  int width = 1280;                // px
  int height = 720;                // px
  double fps = 60.0;               // frames per simulated second; also the --stats/--trace tick of `run`
  Vec2 viewCenter = Vec2::Zero();  // world point at the centre of the frame, m
  double viewHeight = 3.0;         // world units shown vertically, m
  // How the camera moves (render.view's fit, follow or keys), its points resolved to indices. The
  // fixed mode shows viewCenter and viewHeight; follow keeps viewHeight; the first key defaults to both.
  style::ViewStyle view;
};

// `--set path.to.key=value`: replaces (or creates) the node at `path` with `value` parsed as YAML,
// before any validation. `origin` is how the user wrote it, for error messages.
struct Override {
  std::string path;  // `simulation.dt`, `forces[1].ks` or `forces.1.ks`
  std::string value;
  std::string origin;
};

// Parses `path=value` as given to --set; throws ScenarioError when there is no `=` or no path.
Override parseOverride(std::string_view text);

struct Scenario {
  std::string name;
  std::string description;
  std::string file;  // as given to the loader, for messages
  SimulationSettings simulation;
  RenderSettings render;
  System system;
  // What a frame shows beyond its geometry (the `style` section, with a style file and --set
  // merged over it), its selections resolved to particle and body indices.
  style::Style style;
};

// `render --style FILE` (docs/scenarios.md, "Style files"): a file whose top level is a `style`
// section's map, merged over the scenario's section key by key (maps merged, anything else
// replaced) before --set and before validation. Errors in what it gave name it, with its lines.
struct StyleFile {
  std::string text;
  std::string file;  // its path, for messages
};
// Reads a style file, at most maxInputMiB; throws ScenarioError naming it.
StyleFile readStyleFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB);

// Reads and validates a scenario file; the style file (when given) is merged first, then the
// overrides are applied, in order.
Scenario loadScenarioFile(const std::filesystem::path& file, std::span<const Override> overrides = {},
                          std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB, const SceneLimits& limits = {},
                          const StyleFile* styleFile = nullptr);
// The text of a scenario file, at most maxInputMiB; throws ScenarioError naming the file.
std::string readScenarioText(const std::filesystem::path& file,
                             std::uintmax_t maxInputMiB = input::kDefaultMaxInputMiB);
// The same from text in memory; `file` only labels messages.
Scenario loadScenarioText(std::string_view text, const std::string& file, std::span<const Override> overrides = {},
                          const SceneLimits& limits = {}, const StyleFile* styleFile = nullptr);

// How a reference spells point `point` of the system (docs/physics.md §12 --trace): the particle's or
// body's name, `cloth[3][4]` for a grid particle, `#index` for an unnamed particle and `body#j`
// for an unnamed rigid body.
std::string pointName(const Model& model, int point);

// Counts for summaries.
size_t springCount(const System& system);
size_t mouseScriptCount(const System& system);

}  // namespace particles::scenario
