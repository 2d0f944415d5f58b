#include "core/forces/mouse_spring_force.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include <fmt/format.h>

#include "core/system.hpp"

namespace particles {

MouseSpringForce::MouseSpringForce(MouseScript script) : script_(std::move(script)) {
  if (script_.path.empty()) throw std::invalid_argument("mouse script: the path has no points");
  cumulativeLength_.push_back(0.0);
  for (size_t i = 1; i < script_.path.size(); ++i) {
    cumulativeLength_.push_back(cumulativeLength_.back() + (script_.path[i] - script_.path[i - 1]).norm());
  }
}

Vec2 MouseSpringForce::target(double t) const {
  const double total = cumulativeLength_.back();
  const double span = script_.to - script_.from;
  if (total <= 0.0 || span <= 0.0) return script_.path.front();
  const double u = std::clamp((t - script_.from) / span, 0.0, 1.0) * total;
  const auto it = std::upper_bound(cumulativeLength_.begin(), cumulativeLength_.end(), u);
  if (it == cumulativeLength_.end()) return script_.path.back();
  const size_t i = size_t(it - cumulativeLength_.begin());  // segment i-1 → i
  const double segment = cumulativeLength_[i] - cumulativeLength_[i - 1];
  const double w = segment > 0.0 ? (u - cumulativeLength_[i - 1]) / segment : 0.0;
  return (1.0 - w) * script_.path[i - 1] + w * script_.path[i];
}

void MouseSpringForce::holdAt(Vec2 target, double from) {
  script_.path = {target};
  script_.from = from;
  script_.to = std::numeric_limits<double>::infinity();
  cumulativeLength_ = {0.0};
}

void MouseSpringForce::release(double at) {
  script_.to = std::min(script_.to, at);
  script_.from = std::min(script_.from, script_.to);
}

void MouseSpringForce::apply(const Model&, const StateView& s, double t, ForceAccumulator& acc) const {
  if (!activeAt(t)) return;
  const Vec2 f = -script_.ks * (endpointPosition(s, script_.grab) - target(t));
  applyForceAt(s, script_.grab, f, acc);
}

void MouseSpringForce::addJacobians(const Model& model, const StateView&, double t, ForceJacobians& out) const {
  if (!activeAt(t)) return;
  const int p = script_.grab.point(model.layout);
  ForceJacobians::addBlock(out.dfdx, p, p, -script_.ks * Eigen::Matrix2d::Identity());
}

double MouseSpringForce::potentialEnergy(const Model&, const StateView& s, double t) const {
  if (!activeAt(t)) return 0.0;
  return 0.5 * script_.ks * (endpointPosition(s, script_.grab) - target(t)).squaredNorm();
}

double MouseSpringForce::energyScale(const Model&, const StateView& s) const {
  double far = 0.0;
  const Vec2 x = endpointPosition(s, script_.grab);
  for (const Vec2& p : script_.path) far = std::max(far, (p - x).norm());
  return 0.5 * script_.ks * far * far;
}

void MouseSpringForce::validate(const StateLayout& layout) const { checkEndpoint(layout, script_.grab, "mouse"); }

void MouseSpringForce::draw(const StateView& s, double t, Drawing& out, WorkerPool*) const {
  if (activeAt(t)) out.cursors.push_back({target(t), endpointPosition(s, script_.grab)});
}

const KindSpec& mouseKind() {
  static const KindSpec spec{
      .section = "mouse",
      .type = "mouse",
      .summary = "from `from` to `to`, f = −k_s (x − m(t)) pulls the grabbed point towards m(t) moving along "
                 "`path` at constant speed",
      .params = {{.key = "grab", .type = ParamType::endpoint, .required = true, .note = "one particle or body anchor"},
                 {.key = "from", .type = ParamType::number, .unit = "s", .defaultNumber = 0.0, .min = Bound{0.0, true}},
                 {.key = "to", .type = ParamType::number, .unit = "s", .required = true, .note = "> from"},
                 {.key = "path", .type = ParamType::path, .unit = "m", .required = true,
                  .note = "at least one point"},
                 {.key = "ks", .type = ParamType::number, .unit = "N/m", .required = true, .min = Bound{0.0, false}}},
      .build = [](const KindArgs& args, SystemBuilder& out) {
        MouseScript script;
        script.grab = args.points("grab").front();
        script.from = args.number("from");
        script.to = args.number("to");
        if (!(script.to > script.from)) {
          args.fail("to", fmt::format("expected a time after 'from' ({} s), got {}", script.from, script.to));
        }
        script.path = args.path("path");
        script.ks = args.number("ks");
        out.emplaceForce<MouseSpringForce>(std::move(script));
      },
  };
  return spec;
}

}  // namespace particles
