#include "core/constraint.hpp"

namespace particles {

std::vector<ParamSpec> withFeedbackParams(std::vector<ParamSpec> params) {
  const ConstraintFeedback defaults;
  params.push_back({.key = "ks", .type = ParamType::number, .unit = "1/s²", .defaultNumber = defaults.ks,
                    .min = Bound{0.0, true}, .note = "k_s of the drift feedback"});
  params.push_back({.key = "kd", .type = ParamType::number, .unit = "1/s", .defaultNumber = defaults.kd,
                    .min = Bound{0.0, true}, .note = "k_d of the drift feedback"});
  return params;
}

ConstraintFeedback feedbackFrom(const KindArgs& args) { return {args.number("ks"), args.number("kd")}; }

}  // namespace particles
