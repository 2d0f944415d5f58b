#pragma once
// One entry of a kind section (`forces`, `constraints`, `colliders`, `mouse`) as the kind's build
// function reads it (core/kind.hpp): every value is checked against the kind's ParamSpec when read
// (so errors come in the order the kind reads its keys), unknown keys are rejected up front, and
// every failure names the file, line, column and key path. Internal to the scenario loader.

#include <string>
#include <vector>

#include "core/kind.hpp"
#include "scenario/references.hpp"
#include "scenario/yaml_reader.hpp"

namespace particles::scenario::detail {

// What the loader knows of the points declared so far: where they are as the file wrote them, and
// how messages name them.
struct PointBook {
  std::vector<Vec2> particlePos;
  std::vector<Vec2> bodyPos;
  std::vector<double> bodyAngle;
  std::vector<std::string> particleNames;  // as a reference spells them
  std::vector<std::string> bodyNames;

  Vec2 position(const Endpoint& e) const;
  std::string describe(const Endpoint& e) const;
};

class EntryArgs final : public KindArgs {
 public:
  // typed: the entry carries a `type` key (already read) beside the kind's own keys.
  EntryArgs(const KindSpec& kind, const Value& entry, bool typed, const NamedObjects& names, const PointBook& points);

  bool has(std::string_view key) const override;
  double number(std::string_view key) const override;
  Vec2 vec2(std::string_view key) const override;
  std::vector<Endpoint> points(std::string_view key) const override;
  std::vector<Vec2> path(std::string_view key) const override;
  Vec2 initialPosition(const Endpoint& e) const override { return points_.position(e); }
  std::string describe(const Endpoint& e) const override { return points_.describe(e); }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const override;

 private:
  // The kind's spec of `key`; a key the kind does not declare is a bug in the kind (logic_error).
  const ParamSpec& spec(std::string_view key) const;
  // The value of a key that is present, or nothing; fails for a required key that is absent.
  std::optional<Value> value(const ParamSpec& spec) const;

  const KindSpec& kind_;
  MapReader reader_;
  const NamedObjects& names_;
  const PointBook& points_;
};

// The keys an entry of this kind may have: `type` (when typed) and the kind's parameters.
std::vector<std::string_view> allowedKeys(const KindSpec& kind, bool typed);

}  // namespace particles::scenario::detail
