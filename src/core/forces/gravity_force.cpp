#include "core/forces/gravity_force.hpp"

#include "core/system.hpp"

namespace particles {

void GravityForce::apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const {
  applyToPoints(model, s, t, acc.force.data(), 0, model.layout.numPoints());
}

void GravityForce::applyToPoints(const Model& model, const StateView&, double, double* force, int begin,
                                 int end) const {
  const double* mass = model.mass.data();
  for (int i = begin; i < end; ++i) {
    force[2 * i] += mass[i] * g_.x();
    force[2 * i + 1] += mass[i] * g_.y();
  }
}

double GravityForce::potentialEnergy(const Model& model, const StateView& s, double) const {
  double u = 0.0;
  for (int i = 0; i < model.layout.numPoints(); ++i) {
    if (model.invMass[i] != 0.0) u -= model.mass[i] * g_.dot(s.pos(i));
  }
  return u;
}

double GravityForce::energyScale(const Model& model, const StateView& s) const {
  const int n = model.layout.numPoints();
  if (n == 0) return 0.0;
  Vec2 lo = s.pos(0), hi = s.pos(0);
  double movableMass = 0.0;
  for (int i = 0; i < n; ++i) {
    lo = lo.cwiseMin(s.pos(i));
    hi = hi.cwiseMax(s.pos(i));
    if (model.invMass[i] != 0.0) movableMass += model.mass[i];
  }
  return movableMass * g_.norm() * ((hi - lo).norm() + 1.0);
}

const KindSpec& gravityKind() {
  static const KindSpec spec{
      .section = "forces",
      .type = "gravity",
      .summary = "f = m g on every particle and body",
      .params = {{.key = "g", .type = ParamType::vec2, .unit = "m/s²", .defaultVec2 = Vec2(0.0, -9.81)}},
      .build = [](const KindArgs& args, SystemBuilder& out) { out.emplaceForce<GravityForce>(args.vec2("g")); },
  };
  return spec;
}

}  // namespace particles
