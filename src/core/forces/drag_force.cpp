#include "core/forces/drag_force.hpp"

#include "core/system.hpp"

namespace particles {

void DragForce::apply(const Model& model, const StateView& s, double t, ForceAccumulator& acc) const {
  applyToPoints(model, s, t, acc.force.data(), 0, model.layout.numPoints());
  if (angularKd_ != 0.0) {
    acc.torque -= angularKd_ * s.vector().segment(model.layout.omegaOffset(), model.layout.numBodies);
  }
}

void DragForce::applyToPoints(const Model& model, const StateView& s, double, double* force, int begin, int end) const {
  const double* v = s.vector().data() + model.layout.velocityOffset();
  for (int i = 2 * begin; i < 2 * end; ++i) force[i] -= kd_ * v[i];
}

void DragForce::addJacobians(const Model& model, const StateView&, double, ForceJacobians& out) const {
  if (kd_ == 0.0) return;
  for (int i = 0; i < 2 * model.layout.numPoints(); ++i) out.dfdv.emplace_back(i, i, -kd_);
}

const KindSpec& dragKind() {
  static const KindSpec spec{
      .section = "forces",
      .type = "drag",
      .summary = "f = −k_d v on every particle and body; τ = −k_ω ω on every body",
      .params = {{.key = "kd", .type = ParamType::number, .unit = "N·s/m", .required = true, .min = Bound{0.0, true}},
                 {.key = "angular", .type = ParamType::number, .unit = "N·m·s", .defaultNumber = 0.0,
                  .min = Bound{0.0, true}, .note = "k_ω"}},
      .build = [](const KindArgs& args, SystemBuilder& out) {
        const double kd = args.number("kd");
        out.emplaceForce<DragForce>(kd, args.number("angular"));
      },
  };
  return spec;
}

}  // namespace particles
