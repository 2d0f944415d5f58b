#include "core/collider.hpp"

namespace particles {

std::vector<ParamSpec> withPenaltyParams(std::vector<ParamSpec> params) {
  const PenaltyParams defaults;
  params.push_back({.key = "k", .type = ParamType::number, .unit = "N/m²", .defaultNumber = defaults.k,
                    .min = Bound{0.0, false}, .note = "stiffness of f = n k d²"});
  params.push_back({.key = "damping", .type = ParamType::number, .unit = "N·s/m", .defaultNumber = defaults.damping,
                    .min = Bound{0.0, true}, .note = "−c (v·n) n while in contact"});
  return params;
}

PenaltyParams penaltyFrom(const KindArgs& args) { return {args.number("k"), args.number("damping")}; }

}  // namespace particles
