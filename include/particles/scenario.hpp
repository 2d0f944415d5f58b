#pragma once
/// @file
/// A scenario: a YAML description of a system and its simulation and render settings
/// (docs/scenarios.md), loaded and checked as `particles check` checks it.
///
/// @code
/// particles::Scenario cloth = particles::Scenario::load("scenarios/cloth.yaml");
/// cloth.set("dt", 0.005).set("forces[1].ks", "200");
/// cloth.setStyle(particles::Style{.particles = {.colorBy = "speed"}});
/// particles::Simulation sim(cloth);
/// @endcode
///
/// Every error is a particles::ScenarioError naming the file, line, column and key.

#include <memory>
#include <string>
#include <string_view>

#include <particles/choices.hpp>
#include <particles/export.hpp>
#include <particles/style.hpp>

namespace particles {

class Simulation;

/// A scenario: a system to simulate and how to show it, read from a YAML file (docs/scenarios.md)
/// or text, checked whole, and changed by set() as `--set` changes it. Copied and moved freely.
class PARTICLES_API Scenario {
 public:
  /// Reads and validates a scenario file. Throws ScenarioError (a missing or unreadable file, bad
  /// YAML, a bad key or value), naming the file, line and column.
  static Scenario load(const std::string& path);
  /// The same from text in memory (at most 64 MiB, as a file); `label` names it in messages, as a
  /// file would be named.
  static Scenario fromText(std::string_view yaml, const std::string& label = "<text>");

  /// An independent copy: a set() on one does not reach the other.
  Scenario(const Scenario& other);
  /// An independent copy: a set() on one does not reach the other.
  Scenario& operator=(const Scenario& other);
  /// Takes over other's contents; other may then only be destroyed or assigned to.
  Scenario(Scenario&& other) noexcept;
  /// Takes over other's contents; other may then only be destroyed or assigned to.
  Scenario& operator=(Scenario&& other) noexcept;
  ~Scenario();

  /// Replaces (or creates) the value at `path` before validation, as `--set path=value` does: the
  /// path is `simulation.dt`, `forces[1].ks` or `forces.1.ks`, the value is parsed as YAML. The
  /// shorthands `integrator`, `dt`, `duration` and `implicit_solver` are the simulation's keys, as
  /// the options `--integrator`, `--dt`, `--duration` and `--implicit-solver`. The scenario is checked at
  /// once with every value set so far: a bad path, type or value throws ScenarioError, and the
  /// scenario stays as it was. Returns *this, so that calls chain.
  Scenario& set(std::string_view path, std::string_view value);
  /// The same for text: set("integrator", "rk4") is YAML text, not a number or a boolean.
  Scenario& set(std::string_view path, const char* value) { return set(path, std::string_view(value)); }
  /// A number, written so that it reads back as the same double.
  Scenario& set(std::string_view path, double value);

  /// Merges `style` over the scenario's own `style` section, as `particles render --style FILE`
  /// merges a style file (docs/scenarios.md, "Style files"): key by key, maps merged and any other
  /// value (select included) replaced, before every set() value, whatever the order of the calls.
  /// A later setStyle() replaces this one; an empty Style takes it away (the scenario's own section
  /// again). Checked at once with the file's checks and messages: a bad name, colour, length, range
  /// or reference throws ScenarioError whose file() is "style" and whose keyPath() names the field
  /// (`style.particles.color_by`, `style.select[0].trail.width`), without a line or column (the
  /// YAML was written here), and the scenario stays as it was. Simulations made afterwards draw it
  /// (Renderer::render). Returns *this.
  Scenario& setStyle(const Style& style);
  /// The same from a style file's text (YAML: what goes under `style:` in a scenario, at most 64 MiB),
  /// which can also take a scenario's key away with null (`color_by: ~`). Errors name "style" as
  /// their file, with the text's line and column. An empty text takes the style away.
  Scenario& setStyle(std::string_view yaml);
  /// The same for text: setStyle("particles: {color_by: speed}") is YAML, not a Style.
  Scenario& setStyle(const char* yaml) { return setStyle(std::string_view(yaml)); }

  /// What `particles check` prints for a valid scenario: its name, contents, integrator, dt,
  /// duration and steps. A Scenario is checked whole when it is made and at each set(), so this
  /// only reports.
  std::string summary() const;

  /// The scenario's `name` (a copy: a later set() replaces what it was read from).
  std::string name() const;
  /// The scenario's `description` (a copy: a later set() replaces what it was read from).
  std::string description() const;
  std::string file() const;           ///< the path or label it was loaded from
  Integrator integrator() const;      ///< particles::name() spells it as scenarios do: rk4, backward_euler, …
  double dt() const;                  ///< s
  double duration() const;            ///< simulated seconds
  long steps() const;                 ///< steps of dt that cover the duration
  double fps() const;                 ///< the render rate, frames per simulated second
  int particleCount() const;          ///< the particles the system will have
  int bodyCount() const;              ///< the rigid bodies the system will have

  struct Impl;  ///< the library's own, opaque here

 private:
  explicit Scenario(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend class Simulation;
};

}  // namespace particles
