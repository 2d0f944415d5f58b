#pragma once
// How a force, constraint or collider kind is written in a scenario file, as plain data: its keys
// with their types, units, defaults and ranges, and a function that builds the kind's objects
// from validated values. Nothing here knows YAML. The scenario loader reads an entry by this
// description (checking every value against it, with file, line and key in its errors),
// `particles schema` turns it into JSON Schema, and a test checks docs/scenarios.md against it:
// a kind's keys, their validation, their documentation and the kind's drawing (its draw method)
// all come from the kind's own file pair. docs/architecture.md has the checklist for a new kind.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/endpoint.hpp"
#include "core/state.hpp"

namespace particles {

class SystemBuilder;

enum class ParamType {
  number,     // a finite number, within the spec's bounds
  vec2,       // [x, y]
  particle,   // a reference to one particle
  particles,  // one reference or a list of them, resolving to particles only
  endpoint,   // a reference to one particle or rigid-body anchor
  endpoints,  // one reference or a list, resolving to particles or rigid-body anchors
  path,       // a list of at least one [x, y]
};

struct Bound {
  double value;
  bool inclusive;  // ≥ / ≤ rather than > / <
};

struct ParamSpec {
  std::string_view key;
  ParamType type;
  std::string_view unit = "";  // SI, as docs print it ("N/m"); empty when none applies
  bool required = false;
  std::optional<double> defaultNumber = {};  // the default of an optional number
  std::optional<Vec2> defaultVec2 = {};      // the default of an optional [x, y]
  // A default worked out at load time, in words ("the current distance"); empty when the default
  // is a literal above, or when an absent key simply means "not set".
  std::string_view defaultText = "";
  std::optional<Bound> min = {}, max = {};  // for numbers
  std::string_view note = "";               // what else is allowed or meant, for the docs
  // Another key that may stand instead of this one: exactly one of the two is required.
  std::string_view insteadOf = "";
};

// The values of one scenario entry, as the kind's build function sees them: already checked
// against the kind's ParamSpecs (type, range, required) when read, with defaults applied. The
// scenario loader implements it over YAML.
class KindArgs {
 public:
  virtual ~KindArgs() = default;
  virtual bool has(std::string_view key) const = 0;
  virtual double number(std::string_view key) const = 0;
  virtual Vec2 vec2(std::string_view key) const = 0;
  // particle/endpoint keys give one point; particles/endpoints keys one or more.
  virtual std::vector<Endpoint> points(std::string_view key) const = 0;
  virtual std::vector<Vec2> path(std::string_view key) const = 0;
  // Where a point is as the scenario wrote it (for defaults such as a rod's current length).
  virtual Vec2 initialPosition(const Endpoint& e) const = 0;
  // "particle cloth[0][3]", "the anchor [0.2, 0] of rigid body link0": for messages.
  virtual std::string describe(const Endpoint& e) const = 0;
  // Rejects the entry with a message, at the key's position (the entry's when key is empty).
  [[noreturn]] virtual void fail(std::string_view key, const std::string& message) const = 0;
};

struct KindSpec {
  std::string_view section;  // "forces", "constraints", "colliders" or "mouse"
  std::string_view type;     // the entry's `type` ("spring"); for "mouse", the section's one kind
  std::string_view summary;  // one line for people: what it is, its formula
  std::vector<ParamSpec> params;
  // Adds the entry's objects to the builder; throws through args.fail on inconsistent values.
  void (*build)(const KindArgs& args, SystemBuilder& builder);

  const ParamSpec* param(std::string_view key) const;
};

struct KindSection {
  std::string_view key;  // the top-level key of the scenario file
  bool typed;            // entries carry a `type` key naming their kind
};

// The sections that hold kinds, in the order the loader reads them.
const std::vector<KindSection>& kindSections();
// Every kind a scenario file can name, in registration order (core/kinds.cpp).
const std::vector<const KindSpec*>& registeredKinds();
std::vector<const KindSpec*> kindsOf(std::string_view section);
const KindSpec* findKind(std::string_view section, std::string_view type);

}  // namespace particles
