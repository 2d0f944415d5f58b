// particles::Scenario: see include/particles/scenario.hpp.
#include <particles/scenario.hpp>

#include <fmt/format.h>

#include <optional>
#include <utility>

#include "api/guarded_call.hpp"
#include "input/printable_text.hpp"
#include "input/text_file.hpp"
#include "api/scenario_impl.hpp"
#include "api/style_yaml.hpp"
#include "scenario/summary.hpp"

namespace particles {

namespace {

// What a style given to setStyle() is called in messages, as a style file is by its path.
constexpr const char* kStyleLabel = "style";

// The limit of a file (input/text_file.hpp): text from memory is parsed the same way.
void checkTextSize(std::string_view text, const std::string& label, std::string_view what) {
  if (text.size() > input::kDefaultMaxInputMiB * 1024 * 1024) {
    throw ScenarioError(label, 0, 0, "",
                        fmt::format("the text is {} bytes, more than {}'s limit of {} MiB", text.size(), what,
                                    input::kDefaultMaxInputMiB));
  }
}

// set()'s shorthands, the command line's --integrator, --dt, --duration and --implicit-solver.
std::string keyPathOf(std::string_view path) {
  for (std::string_view shorthand : scenario::kSimulationShorthands) {
    if (path == shorthand) return fmt::format("simulation.{}", shorthand);
  }
  return std::string(path);
}

}  // namespace

scenario::Scenario Scenario::Impl::load() const {
  return scenario::loadScenarioText(text, file, overrides, {}, style ? &*style : nullptr);
}

Scenario::Scenario(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Scenario::Scenario(const Scenario& other) : impl_(other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr) {}
Scenario& Scenario::operator=(const Scenario& other) {
  if (this != &other) impl_ = other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr;
  return *this;
}
Scenario::Scenario(Scenario&& other) noexcept = default;
Scenario& Scenario::operator=(Scenario&& other) noexcept = default;
Scenario::~Scenario() = default;

std::unique_ptr<Scenario::Impl> Scenario::Impl::loadedFrom(std::string text, std::string file) {
  auto impl = std::make_unique<Impl>();
  impl->text = std::move(text);
  impl->file = std::move(file);
  impl->loaded = std::make_shared<const scenario::Scenario>(impl->load());
  return impl;
}

Scenario Scenario::load(const std::string& path) {
  return api::guardedCall("Scenario::load",
                          [&] { return Scenario(Impl::loadedFrom(scenario::readScenarioText(path), path)); });
}

Scenario Scenario::fromText(std::string_view yaml, const std::string& label) {
  return api::guardedCall("Scenario::fromText", [&] {
    checkTextSize(yaml, label, "a scenario");
    return Scenario(Impl::loadedFrom(std::string(yaml), label));
  });
}

Scenario& Scenario::set(std::string_view path, std::string_view value) {
  return api::guardedCall("Scenario::set", [&]() -> Scenario& {
    if (!impl_) throw ArgumentError("Scenario::set: this Scenario was moved from");
    if (path.empty()) throw ArgumentError("Scenario::set: the key path is empty");
    const std::string origin = fmt::format("set(\"{}\", \"{}\")", input::shownValue(path), input::shownValue(value));
    impl_->overrides.push_back({keyPathOf(path), std::string(value), origin});
    try {
      impl_->loaded = std::make_shared<const scenario::Scenario>(impl_->load());
    } catch (...) {
      impl_->overrides.pop_back();
      throw;
    }
    return *this;
  });
}

namespace {

// Replaces the scenario's style file with `style` (none: takes it away) and loads it again; on an
// error the scenario stays as it was.
void replaceStyle(Scenario::Impl& impl, std::optional<scenario::StyleFile> style) {
  std::swap(impl.style, style);
  try {
    impl.loaded = std::make_shared<const scenario::Scenario>(impl.load());
  } catch (...) {
    std::swap(impl.style, style);
    throw;
  }
}

}  // namespace

Scenario& Scenario::setStyle(std::string_view yaml) {
  return api::guardedCall("Scenario::setStyle", [&]() -> Scenario& {
    if (!impl_) throw ArgumentError("Scenario::setStyle: this Scenario was moved from");
    checkTextSize(yaml, kStyleLabel, "a style");
    replaceStyle(*impl_,
                 yaml.empty() ? std::nullopt : std::optional<scenario::StyleFile>({std::string(yaml), kStyleLabel}));
    return *this;
  });
}

Scenario& Scenario::setStyle(const Style& style) {
  return api::guardedCall("Scenario::setStyle", [&]() -> Scenario& {
    if (!impl_) throw ArgumentError("Scenario::setStyle: this Scenario was moved from");
    if (api::isEmpty(style)) {
      replaceStyle(*impl_, std::nullopt);
      return *this;
    }
    try {
      replaceStyle(*impl_, scenario::StyleFile{api::styleYaml(style), kStyleLabel});
    } catch (const ScenarioError& e) {
      // A line and column of YAML the caller never saw would only mislead: the key path names the field.
      if (e.file() != kStyleLabel) throw;
      throw ScenarioError(e.file(), 0, 0, e.keyPath(), e.message(), e.origin());
    }
    return *this;
  });
}

Scenario& Scenario::set(std::string_view path, double value) { return set(path, std::string_view(fmt::format("{}", value))); }

namespace {
const scenario::Scenario& loadedOf(const std::unique_ptr<Scenario::Impl>& impl, std::string_view call) {
  if (!impl) throw ArgumentError(fmt::format("Scenario::{}: this Scenario was moved from", call));
  return *impl->loaded;
}
}  // namespace

std::string Scenario::summary() const {
  return api::guardedCall("Scenario::summary", [&] {
    const scenario::Scenario& s = loadedOf(impl_, "summary");
    return scenario::checkSummary(s, s.file);
  });
}

std::string Scenario::name() const {
  return loadedOf(impl_, "name").name;
}
std::string Scenario::description() const {
  return loadedOf(impl_, "description").description;
}
std::string Scenario::file() const {
  return loadedOf(impl_, "file").file;
}
Integrator Scenario::integrator() const {
  return loadedOf(impl_, "integrator").simulation.integrator;
}
double Scenario::dt() const { return loadedOf(impl_, "dt").simulation.dt; }
double Scenario::duration() const { return loadedOf(impl_, "duration").simulation.duration; }
long Scenario::steps() const { return loadedOf(impl_, "steps").simulation.steps(); }
double Scenario::fps() const { return loadedOf(impl_, "fps").render.fps; }
int Scenario::particleCount() const { return loadedOf(impl_, "particleCount").system.layout().numParticles; }
int Scenario::bodyCount() const { return loadedOf(impl_, "bodyCount").system.layout().numBodies; }

}  // namespace particles
