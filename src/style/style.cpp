#include "style/style.hpp"

#include <array>
#include <utility>

namespace particles::style {

namespace {

// One table per enum: each value with its scenario name and, for quantities, its unit.
template <class E>
struct NameRow {
  E value;
  std::string_view name;
  std::string_view unit = "";
};

constexpr std::array kParticleQuantities = {
    NameRow<ParticleQuantity>{ParticleQuantity::speed, "speed", "m/s"},
    NameRow<ParticleQuantity>{ParticleQuantity::velocityX, "velocity_x", "m/s"},
    NameRow<ParticleQuantity>{ParticleQuantity::velocityY, "velocity_y", "m/s"},
    NameRow<ParticleQuantity>{ParticleQuantity::acceleration, "acceleration", "m/s²"},
    NameRow<ParticleQuantity>{ParticleQuantity::kineticEnergy, "kinetic_energy", "J"},
    NameRow<ParticleQuantity>{ParticleQuantity::height, "height", "m"},
    NameRow<ParticleQuantity>{ParticleQuantity::mass, "mass", "kg"},
};
constexpr std::array kSpringQuantities = {
    NameRow<SpringQuantity>{SpringQuantity::strain, "strain", ""},
    NameRow<SpringQuantity>{SpringQuantity::tension, "tension", "N"},
    NameRow<SpringQuantity>{SpringQuantity::energy, "energy", "J"},
};
constexpr std::array kBodyQuantities = {
    NameRow<BodyQuantity>{BodyQuantity::speed, "speed", "m/s"},
    NameRow<BodyQuantity>{BodyQuantity::angularSpeed, "angular_speed", "rad/s"},
};
constexpr std::array kColorbarSubjects = {
    NameRow<ColorbarSubject>{ColorbarSubject::particles, "particles"},
    NameRow<ColorbarSubject>{ColorbarSubject::springs, "springs"},
    NameRow<ColorbarSubject>{ColorbarSubject::bodies, "bodies"},
};
constexpr std::array kColorbarPositions = {
    NameRow<ColorbarPosition>{ColorbarPosition::right, "right"},
    NameRow<ColorbarPosition>{ColorbarPosition::left, "left"},
    NameRow<ColorbarPosition>{ColorbarPosition::top, "top"},
    NameRow<ColorbarPosition>{ColorbarPosition::bottom, "bottom"},
};
constexpr std::array kArrowQuantities = {
    NameRow<ArrowQuantity>{ArrowQuantity::velocity, "velocity", "m/s"},
    NameRow<ArrowQuantity>{ArrowQuantity::force, "force", "N"},
};

template <class Table>
auto fromName(const Table& table, std::string_view name) -> std::optional<decltype(table[0].value)> {
  for (const auto& row : table) {
    if (row.name == name) return row.value;
  }
  return std::nullopt;
}

template <class Table, class E>
const auto& rowOf(const Table& table, E value) {
  for (const auto& row : table) {
    if (row.value == value) return row;
  }
  return table[0];  // unreachable for a valid enum value
}

template <class Table>
std::vector<std::string> namesOf(const Table& table) {
  std::vector<std::string> names;
  for (const auto& row : table) names.emplace_back(row.name);
  return names;
}

}  // namespace

bool Style::isPlain() const {
  const Style plain;
  return !particles.colorBy && !particles.color && !particles.radius && springs.colorBy == plain.springs.colorBy &&
         !springs.colormap && !springs.rangeGiven && !springs.color && !springs.width && !bodies.colorBy &&
         !bodies.color && !bodies.outline && !colorbar && title.empty() && !scaleBar && select.empty();
}

std::optional<ParticleQuantity> particleQuantityFromName(std::string_view n) { return fromName(kParticleQuantities, n); }
std::optional<SpringQuantity> springQuantityFromName(std::string_view n) { return fromName(kSpringQuantities, n); }
std::optional<BodyQuantity> bodyQuantityFromName(std::string_view n) { return fromName(kBodyQuantities, n); }
std::optional<ColorbarSubject> colorbarSubjectFromName(std::string_view n) { return fromName(kColorbarSubjects, n); }
std::optional<ColorbarPosition> colorbarPositionFromName(std::string_view n) {
  return fromName(kColorbarPositions, n);
}
std::optional<ArrowQuantity> arrowQuantityFromName(std::string_view n) { return fromName(kArrowQuantities, n); }

std::string_view nameOf(ParticleQuantity q) { return rowOf(kParticleQuantities, q).name; }
std::string_view nameOf(SpringQuantity q) { return rowOf(kSpringQuantities, q).name; }
std::string_view nameOf(BodyQuantity q) { return rowOf(kBodyQuantities, q).name; }
std::string_view nameOf(ColorbarSubject s) { return rowOf(kColorbarSubjects, s).name; }
std::string_view nameOf(ColorbarPosition p) { return rowOf(kColorbarPositions, p).name; }
std::string_view nameOf(ArrowQuantity q) { return rowOf(kArrowQuantities, q).name; }

std::vector<std::string> particleQuantityNames() { return namesOf(kParticleQuantities); }
std::vector<std::string> springQuantityNames() { return namesOf(kSpringQuantities); }
std::vector<std::string> bodyQuantityNames() { return namesOf(kBodyQuantities); }
std::vector<std::string> colorbarSubjectNames() { return namesOf(kColorbarSubjects); }
std::vector<std::string> colorbarPositionNames() { return namesOf(kColorbarPositions); }
std::vector<std::string> arrowQuantityNames() { return namesOf(kArrowQuantities); }

std::string_view unitOf(ParticleQuantity q) { return rowOf(kParticleQuantities, q).unit; }
std::string_view unitOf(SpringQuantity q) { return rowOf(kSpringQuantities, q).unit; }
std::string_view unitOf(BodyQuantity q) { return rowOf(kBodyQuantities, q).unit; }

}  // namespace particles::style
