// The scenario loader: one reader per top-level section of docs/physics.md §11, in the order the sections
// depend on each other (things that have names before the references to them). Keys, defaults and
// ranges here and in docs/scenarios.md change together.
#include "scenario/scenario.hpp"

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "input/printable_text.hpp"
#include "core/forces/damped_spring_force.hpp"
#include "core/grid.hpp"
#include "core/kind.hpp"
#include "input/closest_name.hpp"
#include "input/text_file.hpp"
#include "scenario/budget.hpp"
#include "scenario/entry_args.hpp"
#include "scenario/key_paths.hpp"
#include "scenario/part_reader.hpp"
#include "scenario/references.hpp"
#include "scenario/style_reader.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario {

namespace {

using detail::MapReader;
using detail::NamedObjects;
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
    type.fail(fmt::format(
        "unknown type {}{}; expected one of {}", input::quotedValue(name),
        suggestion.empty() ? std::string() : fmt::format(" (did you mean {}?)", input::quotedValue(suggestion)),
        fmt::join(types, ", ")));
  }
  return name;
}

int lineOf(const Value& v) {
  return v.node().Mark().is_null() ? 0 : v.node().Mark().line + 1;
}

}  // namespace

// Declared in part_reader.hpp, which reads parts of a loaded file again with it.
class detail::Loader {
 public:
  Loader(detail::Source source, const SceneLimits& limits) : source_(std::move(source)), limits_(limits) {}

  Scenario load(const YAML::Node& document) {
    const Value root(source_, document, "", document.Mark());
    detail::checkSceneBudget(root, limits_);
    const MapReader top(root, topKeys());
    std::string name = top.required("name").string();
    std::string description = top.optional("description") ? top.optional("description")->string() : "";
    const SimulationSettings simulation = readSimulation(top.optional("simulation"));
    RenderSettings render = readRender(top.optional("render"));

    if (auto v = top.optional("particles")) readParticles(*v);
    if (auto v = top.optional("grids")) readGrids(*v);
    if (auto v = top.optional("rigid_bodies")) readBodies(*v);
    for (const KindSection& section : kindSections()) {
      if (auto v = top.optional(section.key)) readKinds(section, *v, builder_);
    }
    render.view = readCamera(top.optional("render"), render);

    try {
      Scenario scenario{
          std::move(name), std::move(description), source_.file, simulation, render, builder_.build(), {}};
      scenario.system.setImplicitSolver(simulation.implicitSolver);
      // After the build: a colour bar explains a class of shapes the scene has (springs included).
      const StateLayout& layout = scenario.system.layout();
      scenario.style = detail::readStyle(
          top.optional("style"), names_,
          {layout.numParticles, static_cast<long long>(springCount(scenario.system)), layout.numBodies});
      return scenario;
    } catch (const std::invalid_argument& e) {
      // The checks above should have caught everything the builder checks; say so if not.
      throw ScenarioError(source_.file, 0, 0, "", fmt::format("the scenario is inconsistent: {}", e.what()));
    }
  }

  // After load(document): one part of the same tree, changed since in that part alone, read again
  // as load() reads it, against the names and points load() declared (part_reader.hpp).
  void setOverridden(std::vector<std::pair<std::string, std::string>> overridden) {
    source_.overridden = std::move(overridden);
  }
  SimulationSettings readSimulationAgain(const YAML::Node& document) {
    return readSimulation(topOf(document).optional("simulation"));
  }
  RenderSettings readRenderAgain(const YAML::Node& document) {
    const std::optional<Value> section = topOf(document).optional("render");
    RenderSettings r = readRender(section);
    r.view = readCamera(section, r);
    return r;
  }
  void readEntryAgain(const YAML::Node& document, const detail::FilePart& part) {
    using Kind = detail::FilePart::Kind;
    const MapReader top = topOf(document);
    std::optional<Name> name;
    switch (part.kind) {
      case Kind::particle: readParticle(top.required("particles").item(part.index), name); break;
      case Kind::grid: readGrid(top.required("grids").item(part.index), name); break;
      case Kind::rigidBody: readBody(top.required("rigid_bodies").item(part.index), name); break;
      case Kind::kindEntry: {
        const KindSection& section = kindSections().at(part.section);
        SystemBuilder scratch;  // what the entry builds is of no use here, only its checks
        readKind(kindsIn(section), top.required(section.key).item(part.index), scratch);
        break;
      }
      case Kind::simulation:
      case Kind::render: throw std::logic_error("readEntryAgain reads entries of lists, not settings");
    }
  }

 private:
  // A name as the file writes it, where it is written, declared after the rest of its entry is read.
  struct Name {
    std::string text;
    Value at;
  };

  static std::vector<std::string_view> topKeys() {
    std::vector<std::string_view> keys = {"name",      "description", "simulation",  "render",
                                          "particles", "grids",       "rigid_bodies"};
    for (const KindSection& section : kindSections()) keys.push_back(section.key);
    keys.push_back("style");
    return keys;
  }
  MapReader topOf(const YAML::Node& document) const {
    return MapReader(Value(source_, document, "", document.Mark()), topKeys());
  }

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
        i->fail(fmt::format(
            "unknown integrator {}{}; expected one of {}", input::quotedValue(name),
            suggestion.empty() ? std::string() : fmt::format(" (did you mean {}?)", input::quotedValue(suggestion)),
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
        solver->fail(fmt::format("unknown implicit solver {}; expected one of {}, {}, {}", input::quotedValue(name),
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
    const MapReader m(*v, renderKeys());
    if (auto size = m.optional("size")) {
      if (!size->isSequence() || size->node().size() != 2) {
        size->fail(fmt::format("expected [width, height] in pixels, {}", size->found()));
      }
      r.width = int(size->item(0).integer(1, kMaxImageSide));
      r.height = int(size->item(1).integer(1, kMaxImageSide));
    }
    if (auto fps = m.optional("fps")) r.fps = fps->inRange(kMinFps, kMaxFps);
    if (auto view = m.optional("view")) {
      const MapReader vm(*view, detail::viewKeys());
      if (auto c = vm.optional("center")) r.viewCenter = c->vec2();
      if (auto h = vm.optional("height")) r.viewHeight = h->positive();
    }
    return r;
  }
  static std::vector<std::string_view> renderKeys() { return {"size", "fps", "view"}; }
  // render.view's camera modes name points: read once every name is declared.
  style::ViewStyle readCamera(const std::optional<Value>& section, const RenderSettings& start) const {
    if (!section) return {};
    return detail::readViewStyle(MapReader(*section, renderKeys()).optional("view"), names_, start);
  }

  // --- things with names -------------------------------------------------------------------------
  // An entry read and checked, its name too (when it has one) but not yet declared: the readers
  // below declare it, readEntryAgain does not (it is declared already).
  ParticleSpec readParticle(const Value& item, std::optional<Name>& name) {
    const MapReader m(item, {"name", "pos", "vel", "mass", "fixed"});
    ParticleSpec p;
    p.pos = m.required("pos").vec2();
    if (auto v = m.optional("vel")) p.vel = v->vec2();
    if (auto v = m.optional("mass")) p.mass = v->positive();
    if (auto v = m.optional("fixed")) p.fixed = v->boolean();
    if (auto v = m.optional("name")) {
      p.name = v->string();
      name = Name{p.name, *v};
    }
    return p;
  }

  void readParticles(const Value& list) {
    for (const Value& item : list.items()) {
      std::optional<Name> name;
      const ParticleSpec p = readParticle(item, name);
      if (name)
        names_.add(name->at, p.name, {NamedObjects::Kind::particle, builder_.numParticles(), {}, lineOf(name->at)});
      addParticle(p);
      book_.particleNames.push_back(p.name.empty() ? fmt::format("#{}", book_.particleNames.size()) : p.name);
    }
  }

  GridSpec readGrid(const Value& item, std::optional<Name>& nameAt) {
    const MapReader m(item, {"name", "origin", "size", "spacing", "mass", "springs"});
    GridSpec g;
    const Value name = m.required("name");
    g.name = name.string();
    nameAt = Name{g.name, name};
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
    return g;
  }

  void readGrids(const Value& list) {
    for (const Value& item : list.items()) {
      std::optional<Name> name;
      const GridSpec g = readGrid(item, name);
      const bool hasSprings = g.structural || g.shear || g.flexion;
      DampedSpringForce scratch;
      const GridIndices indices = addGrid(builder_, hasSprings ? builder_.sharedForce<DampedSpringForce>("grid springs") : scratch, g);
      for (int r = 0; r < g.rows; ++r)
        for (int c = 0; c < g.cols; ++c) {
          book_.particlePos.push_back(g.origin + Vec2(c * g.spacing.x(), -r * g.spacing.y()));
          book_.particleNames.push_back(fmt::format("{}[{}][{}]", g.name, r, c));
        }
      names_.add(name->at, g.name, {NamedObjects::Kind::grid, -1, indices, lineOf(name->at)});
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

  RigidBodySpec readBody(const Value& item, std::optional<Name>& name) {
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
      name = Name{b.name, *v};
    }
    return b;
  }

  void readBodies(const Value& list) {
    for (const Value& item : list.items()) {
      std::optional<Name> name;
      const RigidBodySpec b = readBody(item, name);
      if (name) names_.add(name->at, b.name, {NamedObjects::Kind::body, builder_.numBodies(), {}, lineOf(name->at)});
      builder_.addRigidBody(b);
      book_.bodyPos.push_back(b.pos);
      book_.bodyAngle.push_back(b.angle);
      book_.bodyNames.push_back(b.name.empty() ? fmt::format("body#{}", book_.bodyNames.size()) : b.name);
    }
  }

  // --- forces, constraints, colliders, the mouse: kinds described in the core ----------------------
  // The kinds of a section and their type names.
  struct SectionKinds {
    const KindSection& section;
    std::vector<const KindSpec*> kinds;
    std::vector<std::string> types;
  };
  static SectionKinds kindsIn(const KindSection& section) {
    SectionKinds out{section, kindsOf(section.key), {}};
    for (const KindSpec* k : out.kinds) out.types.emplace_back(k->type);
    return out;
  }

  // An entry reads the names and points declared before it, and nothing of the other entries.
  void readKind(const SectionKinds& in, const Value& item, SystemBuilder& builder) const {
    const KindSpec& kind = in.section.typed ? *findKind(in.section.key, readType(item, in.types)) : *in.kinds.front();
    const detail::EntryArgs args(kind, item, in.section.typed, names_, book_);
    kind.build(args, builder);
  }

  void readKinds(const KindSection& section, const Value& list, SystemBuilder& builder) const {
    const SectionKinds in = kindsIn(section);
    for (const Value& item : list.items()) readKind(in, item, builder);
  }

  // --- helpers -------------------------------------------------------------------------------------
  void addParticle(const ParticleSpec& p) {
    builder_.addParticle(p);
    book_.particlePos.push_back(p.pos);
    names_.numParticles = builder_.numParticles();
  }

  detail::Source source_;
  const SceneLimits& limits_;
  NamedObjects names_;
  SystemBuilder builder_;
  detail::PointBook book_;
};

namespace {

// yaml-cpp's conversions that can throw are not used; anything it still throws is reported at its
// mark rather than escaping as an unexplained exception.
template <class Read>
auto readingYaml(const std::string& file, const Read& read) {
  try {
    return read();
  } catch (const YAML::Exception& e) {
    throw ScenarioError(file, e.mark.is_null() ? 0 : e.mark.line + 1, e.mark.is_null() ? 0 : e.mark.column + 1, "",
                        fmt::format("cannot read YAML: {}", e.msg));
  }
}

Scenario loadDocument(const std::string& text, const std::string& file, std::span<const Override> overrides,
                      const SceneLimits& limits, const StyleFile* styleFile) {
  const detail::NodeLimit nodeLimit = detail::NodeLimit::scenario(std::uintmax_t(limits.nodes));
  YAML::Node root = detail::loadOneDocument(text, file, nullptr, nodeLimit);
  if (!root.IsMap()) {
    const YAML::Mark m = root.Mark();
    throw ScenarioError(file, m.line + 1, m.column + 1, "", "expected a scenario (a map of keys such as 'name')");
  }
  detail::Source source{file, {}, {}};
  // The style file first: --set may change what it gave, as it may change the scenario.
  if (styleFile) source.fromFiles = detail::mergeStyleFile(root, *styleFile, nodeLimit);
  for (const Override& o : overrides) source.overridden.emplace_back(detail::applyOverride(root, o, file), o.origin);
  return readingYaml(file, [&] { return detail::Loader(std::move(source), limits).load(root); });
}

}  // namespace

namespace detail {

PartReader::PartReader(std::string file, const SceneLimits& limits)
    : file_(std::move(file)),
      limits_(std::make_unique<SceneLimits>(limits)),
      loader_(std::make_unique<Loader>(Source{file_, {}, {}}, *limits_)) {}
PartReader::~PartReader() = default;
PartReader::PartReader(PartReader&&) noexcept = default;
PartReader& PartReader::operator=(PartReader&&) noexcept = default;

Scenario PartReader::load(const YAML::Node& document, OverriddenPaths overridden) {
  loader_->setOverridden(std::move(overridden));
  return readingYaml(file_, [&] { return loader_->load(document); });
}

SimulationSettings PartReader::readSimulation(const YAML::Node& document, OverriddenPaths overridden) {
  loader_->setOverridden(std::move(overridden));
  return readingYaml(file_, [&] { return loader_->readSimulationAgain(document); });
}

RenderSettings PartReader::readRender(const YAML::Node& document, OverriddenPaths overridden) {
  loader_->setOverridden(std::move(overridden));
  return readingYaml(file_, [&] { return loader_->readRenderAgain(document); });
}

void PartReader::readEntry(const YAML::Node& document, const FilePart& part, OverriddenPaths overridden) {
  loader_->setOverridden(std::move(overridden));
  readingYaml(file_, [&] {
    loader_->readEntryAgain(document, part);
    return 0;
  });
}

}  // namespace detail

long SimulationSettings::steps() const {
  // The tolerance keeps 10 s / 0.01 s at 1000 steps despite rounding in the division.
  return std::max(1L, long(std::ceil(duration / dt - 1e-9)));
}

Scenario loadScenarioText(std::string_view text, const std::string& file, std::span<const Override> overrides,
                          const SceneLimits& limits, const StyleFile* styleFile) {
  return loadDocument(std::string(text), file, overrides, limits, styleFile);
}

std::string readScenarioText(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  try {
    return input::readTextFile(file, maxInputMiB);
  } catch (const input::ReadError& e) {
    throw ScenarioError(file.string(), 0, 0, "", e.what());
  }
}

Scenario loadScenarioFile(const std::filesystem::path& file, std::span<const Override> overrides,
                          std::uintmax_t maxInputMiB, const SceneLimits& limits, const StyleFile* styleFile) {
  return loadDocument(readScenarioText(file, maxInputMiB), file.string(), overrides, limits, styleFile);
}

StyleFile readStyleFile(const std::filesystem::path& file, std::uintmax_t maxInputMiB) {
  return {readScenarioText(file, maxInputMiB), file.string()};
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
