// The scenario loader: one reader per top-level section of docs/physics.md §11, in the order the sections
// depend on each other (things that have names before the references to them). Keys, defaults and
// ranges here and in docs/scenarios.md change together.
#include "scenario/scenario.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "core/forces/damped_spring_force.hpp"
#include "core/grid.hpp"
#include "core/kind.hpp"
#include "input/closest_name.hpp"
#include "input/text_file.hpp"
#include "scenario/budget.hpp"
#include "scenario/entry_args.hpp"
#include "scenario/key_paths.hpp"
#include "scenario/references.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using detail::MapReader;
using detail::NameTable;
using detail::PointKind;
using detail::Value;


// The type key of a list entry, checked against the kinds the section knows.
std::string readType(const Value& entry, const std::vector<std::string>& types) {
  if (!entry.isMap()) entry.fail(fmt::format("expected a map with a 'type' key, {}", entry.found()));
  const YAML::Node typeNode = entry.node()["type"];
  const Value type = entry.child(typeNode, entry.path() + ".type", entry.node().Mark());
  if (!typeNode.IsDefined()) {
    entry.child(entry.node(), entry.path() + ".type", YAML::Mark::null_mark())
        .fail(fmt::format("missing required key 'type' (one of {})", fmt::join(types, ", ")));
  }
  const std::string name = type.string();
  if (std::find(types.begin(), types.end(), name) == types.end()) {
    const std::string suggestion = input::closestName(name, types);
    type.fail(fmt::format("unknown type '{}'{}; expected one of {}", name,
                          suggestion.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", suggestion),
                          fmt::join(types, ", ")));
  }
  return name;
}

int lineOf(const Value& v) {
  return v.node().Mark().is_null() ? 0 : v.node().Mark().line + 1;
}

class Loader {
 public:
  Loader(detail::Source source, const SceneLimits& limits) : source_(std::move(source)), limits_(limits) {}

  Scenario load(const YAML::Node& document) {
    const Value root(source_, document, "", document.Mark());
    detail::checkSceneBudget(root, limits_);
    std::vector<std::string_view> keys = {"name", "description", "simulation", "render", "particles", "grids",
                                          "rigid_bodies"};
    for (const KindSection& section : kindSections()) keys.push_back(section.key);
    const MapReader top(root, keys);
    std::string name = top.required("name").string();
    std::string description = top.optional("description") ? top.optional("description")->string() : "";
    const SimulationSettings simulation = readSimulation(top.optional("simulation"));
    const RenderSettings render = readRender(top.optional("render"));

    if (auto v = top.optional("particles")) readParticles(*v);
    if (auto v = top.optional("grids")) readGrids(*v);
    if (auto v = top.optional("rigid_bodies")) readBodies(*v);
    for (const KindSection& section : kindSections()) {
      if (auto v = top.optional(section.key)) readKinds(section, *v);
    }

    try {
      Scenario scenario{std::move(name), std::move(description), source_.file, simulation, render, builder_.build()};
      scenario.system.setImplicitSolver(simulation.implicitSolver);
      return scenario;
    } catch (const std::invalid_argument& e) {
      // The checks above should have caught everything the builder checks; say so if not.
      throw ScenarioError(source_.file, 0, 0, "", fmt::format("the scenario is inconsistent: {}", e.what()));
    }
  }

 private:
  // --- settings ----------------------------------------------------------------------------------
  SimulationSettings readSimulation(const std::optional<Value>& v) {
    SimulationSettings s;
    if (!v) return s;
    const MapReader m(*v, {"integrator", "dt", "duration", "implicit_solver"});
    if (auto i = m.optional("integrator")) {
      const std::string name = i->string();
      const auto integrator = integratorFromName(name);
      if (!integrator) {
        std::vector<std::string> known;
        for (Integrator k : allIntegrators()) known.emplace_back(integratorName(k));
        const std::string suggestion = input::closestName(name, known);
        i->fail(fmt::format("unknown integrator '{}'{}; expected one of {}", name,
                            suggestion.empty() ? std::string() : fmt::format(" (did you mean '{}'?)", suggestion),
                            fmt::join(known, ", ")));
      }
      s.integrator = *integrator;
    }
    if (auto dt = m.optional("dt")) s.dt = dt->positive();
    if (auto d = m.optional("duration")) s.duration = d->positive();
    if (auto solver = m.optional("implicit_solver")) {
      const std::string name = solver->string();
      const auto chosen = implicitSolverFromName(name);
      if (!chosen) {
        solver->fail(fmt::format("unknown implicit solver '{}'; expected one of {}, {}, {}", name,
                                 implicitSolverName(ImplicitSolver::automatic),
                                 implicitSolverName(ImplicitSolver::direct), implicitSolverName(ImplicitSolver::cg)));
      }
      s.implicitSolver = *chosen;
    }
    if (double(s.duration) / s.dt > double(kMaxSteps)) {
      const Value at = m.optional("dt") ? *m.optional("dt") : m.self();
      at.fail(fmt::format("dt = {} s over duration = {} s makes more than {} steps", detail::formatNumber(s.dt),
                          detail::formatNumber(s.duration), kMaxSteps));
    }
    return s;
  }

  RenderSettings readRender(const std::optional<Value>& v) {
    RenderSettings r;
    if (!v) return r;
    const MapReader m(*v, {"size", "fps", "view"});
    if (auto size = m.optional("size")) {
      if (!size->isSequence() || size->node().size() != 2) {
        size->fail(fmt::format("expected [width, height] in pixels, {}", size->found()));
      }
      r.width = int(size->item(0).integer(1, kMaxImageSide));
      r.height = int(size->item(1).integer(1, kMaxImageSide));
    }
    if (auto fps = m.optional("fps")) r.fps = fps->inRange(kMinFps, kMaxFps);
    if (auto view = m.optional("view")) {
      const MapReader vm(*view, {"center", "height"});
      if (auto c = vm.optional("center")) r.viewCenter = c->vec2();
      if (auto h = vm.optional("height")) r.viewHeight = h->positive();
    }
    return r;
  }

  // --- things with names -------------------------------------------------------------------------
  void readParticles(const Value& list) {
    for (const Value& item : list.items()) {
      const MapReader m(item, {"name", "pos", "vel", "mass", "fixed"});
      ParticleSpec p;
      p.pos = m.required("pos").vec2();
      if (auto v = m.optional("vel")) p.vel = v->vec2();
      if (auto v = m.optional("mass")) p.mass = v->positive();
      if (auto v = m.optional("fixed")) p.fixed = v->boolean();
      if (auto v = m.optional("name")) {
        p.name = v->string();
        names_.add(*v, p.name, {NameTable::Kind::Particle, builder_.numParticles(), {}, lineOf(*v)});
      }
      addParticle(p);
      book_.particleNames.push_back(p.name.empty() ? fmt::format("#{}", book_.particleNames.size()) : p.name);
    }
  }

  void readGrids(const Value& list) {
    for (const Value& item : list.items()) {
      const MapReader m(item, {"name", "origin", "size", "spacing", "mass", "springs"});
      GridSpec g;
      const Value name = m.required("name");
      g.name = name.string();
      if (auto v = m.optional("origin")) g.origin = v->vec2();
      const Value size = m.required("size");
      if (!size.isSequence() || size.node().size() != 2) {
        size.fail(fmt::format("expected [columns, rows], {}", size.found()));
      }
      g.cols = int(size.item(0).integer(1, kMaxGridSide));
      g.rows = int(size.item(1).integer(1, kMaxGridSide));
      if (auto v = m.optional("spacing")) g.spacing = v->positiveVec2();
      if (auto v = m.optional("mass")) g.mass = v->positive();
      if (auto springs = m.optional("springs")) {
        const MapReader sm(*springs, {"structural", "shear", "flexion"});
        if (auto f = sm.optional("structural")) g.structural = readSpringFamily(*f);
        if (auto f = sm.optional("shear")) g.shear = readSpringFamily(*f);
        if (auto f = sm.optional("flexion")) g.flexion = readSpringFamily(*f);
      }
      const bool hasSprings = g.structural || g.shear || g.flexion;
      DampedSpringForce scratch;
      const GridIndices indices = addGrid(builder_, hasSprings ? builder_.sharedForce<DampedSpringForce>("grid springs") : scratch, g);
      for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
          book_.particlePos.push_back(g.origin + Vec2(c * g.spacing.x(), -r * g.spacing.y()));
          book_.particleNames.push_back(fmt::format("{}[{}][{}]", g.name, r, c));
        }
      names_.add(name, g.name, {NameTable::Kind::Grid, -1, indices, lineOf(name)});
      names_.numParticles = builder_.numParticles();
    }
  }

  GridSpringFamily readSpringFamily(const Value& v) {
    const MapReader m(v, {"ks", "kd"});
    GridSpringFamily f{0.0, 0.0, 0.0};
    const Value ks = m.required("ks");
    if (ks.isSequence()) {
      if (ks.node().size() != 2) ks.fail(fmt::format("expected a stiffness or [top, bottom], {}", ks.found()));
      f.ksTop = ks.item(0).nonNegative();
      f.ksBottom = ks.item(1).nonNegative();
    } else {
      f.ksTop = f.ksBottom = ks.nonNegative();
    }
    if (auto kd = m.optional("kd")) f.kd = kd->nonNegative();
    return f;
  }

  void readBodies(const Value& list) {
    for (const Value& item : list.items()) {
      const MapReader m(item, {"name", "pos", "angle", "size", "mass", "vel", "omega"});
      RigidBodySpec b;
      b.pos = m.required("pos").vec2();
      b.size = m.required("size").positiveVec2();
      if (auto v = m.optional("angle")) b.angle = v->number();
      if (auto v = m.optional("mass")) b.mass = v->positive();
      if (auto v = m.optional("vel")) b.vel = v->vec2();
      if (auto v = m.optional("omega")) b.omega = v->number();
      if (auto v = m.optional("name")) {
        b.name = v->string();
        names_.add(*v, b.name, {NameTable::Kind::Body, builder_.numBodies(), {}, lineOf(*v)});
      }
      builder_.addRigidBody(b);
      book_.bodyPos.push_back(b.pos);
      book_.bodyAngle.push_back(b.angle);
      book_.bodyNames.push_back(b.name.empty() ? fmt::format("body#{}", book_.bodyNames.size()) : b.name);
    }
  }

  // --- forces, constraints, colliders, the mouse: kinds described in the core ----------------------
  void readKinds(const KindSection& section, const Value& list) {
    const std::vector<const KindSpec*> kinds = kindsOf(section.key);
    std::vector<std::string> types;
    for (const KindSpec* k : kinds) types.emplace_back(k->type);
    for (const Value& item : list.items()) {
      const KindSpec& kind = section.typed ? *findKind(section.key, readType(item, types)) : *kinds.front();
      const detail::EntryArgs args(kind, item, section.typed, names_, book_);
      kind.build(args, builder_);
    }
  }

  // --- helpers -------------------------------------------------------------------------------------
  void addParticle(const ParticleSpec& p) {
    builder_.addParticle(p);
    book_.particlePos.push_back(p.pos);
    names_.numParticles = builder_.numParticles();
  }

  detail::Source source_;
  const SceneLimits& limits_;
  NameTable names_;
  SystemBuilder builder_;
  detail::PointBook book_;
};

Scenario loadDocument(const std::string& text, const std::string& file, std::span<const Override> overrides,
                      const SceneLimits& limits) {
  YAML::Node root = detail::loadOneDocument(text, file);
  if (!root.IsMap()) {
    const YAML::Mark m = root.Mark();
    throw ScenarioError(file, m.line + 1, m.column + 1, "", "expected a scenario (a map of keys such as 'name')");
  }
  detail::Source source{file, {}};
  for (const Override& o : overrides) source.overridden.emplace_back(detail::applyOverride(root, o, file), o.origin);
  try {
    return Loader(std::move(source), limits).load(root);
  } catch (const YAML::Exception& e) {
    // The loader only uses non-throwing conversions; anything yaml-cpp still throws is reported
    // at its mark rather than escaping as an unexplained exception.
    throw ScenarioError(file, e.mark.is_null() ? 0 : e.mark.line + 1, e.mark.is_null() ? 0 : e.mark.column + 1, "",
                        fmt::format("cannot read YAML: {}", e.msg));
  }
}

}  // namespace

long SimulationSettings::steps() const {
  // The tolerance keeps 10 s / 0.01 s at 1000 steps despite rounding in the division.
  return std::max(1L, long(std::ceil(duration / dt - 1e-9)));
}

Scenario loadScenarioText(std::string_view text, const std::string& file, std::span<const Override> overrides,
                          const SceneLimits& limits) {
  return loadDocument(std::string(text), file, overrides, limits);
}

std::string readScenarioText(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  try {
    return input::readTextFile(file, maxInputMiB);
  } catch (const input::ReadError& e) {
    throw ScenarioError(file.string(), 0, 0, "", e.what());
  }
}

Scenario loadScenarioFile(const std::filesystem::path& file, std::span<const Override> overrides,
                          std::uintmax_t maxInputMiB, const SceneLimits& limits) {
  return loadDocument(readScenarioText(file, maxInputMiB), file.string(), overrides, limits);
}

size_t springCount(const System& system) {
  size_t n = 0;
  for (const auto& f : system.forces()) n += f->isSpringSet() ? f->count() : 0;
  return n;
}

size_t mouseScriptCount(const System& system) {
  // A time-dependent force is a script moving a target: the mouse is the one such kind.
  size_t n = 0;
  for (const auto& f : system.forces()) n += f->isTimeDependent() ? f->count() : 0;
  return n;
}

}  // namespace particles::scenario
