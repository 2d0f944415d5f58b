#include "style/quantity.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace particles::style {

namespace {

// The drawing's list `name` must have one entry per shape.
template <class List>
const List& required(const List& list, size_t shapes, const char* name) {
  if (list.size() != shapes) {
    throw std::invalid_argument(std::string("the drawing lacks ") + name + " (System::draw's DrawDetail)");
  }
  return list;
}

bool usesVelocities(const Style& s) {
  const auto p = s.particles.colorBy;
  const bool particles = p == ParticleQuantity::speed || p == ParticleQuantity::velocityX ||
                         p == ParticleQuantity::velocityY || p == ParticleQuantity::kineticEnergy;
  const bool arrows = std::any_of(s.select.begin(), s.select.end(), [](const Selection& sel) {
    return sel.arrow && sel.arrow->of == ArrowQuantity::velocity;
  });
  return particles || s.bodies.colorBy.has_value() || arrows;
}

bool usesAccelerations(const Style& s) {
  const bool arrows = std::any_of(s.select.begin(), s.select.end(), [](const Selection& sel) {
    return sel.arrow && sel.arrow->of == ArrowQuantity::force;
  });
  return s.particles.colorBy == ParticleQuantity::acceleration || arrows;
}

}  // namespace

DrawDetail drawDetailFor(const Style& style) {
  DrawDetail detail;
  detail.velocities = usesVelocities(style);
  detail.accelerations = usesAccelerations(style);
  const auto p = style.particles.colorBy;
  // Force arrows are m·a: they need the masses as well.
  detail.masses = p == ParticleQuantity::mass || p == ParticleQuantity::kineticEnergy || detail.accelerations;
  return detail;
}

void particleValues(const Drawing& f, ParticleQuantity q, std::vector<double>& out) {
  const size_t n = f.particles.size();
  out.resize(n);
  switch (q) {
    case ParticleQuantity::speed: {
      const auto& v = required(f.particleVelocities, n, "particle velocities");
      for (size_t i = 0; i < n; ++i) out[i] = v[i].norm();
      break;
    }
    case ParticleQuantity::velocityX: {
      const auto& v = required(f.particleVelocities, n, "particle velocities");
      for (size_t i = 0; i < n; ++i) out[i] = v[i].x();
      break;
    }
    case ParticleQuantity::velocityY: {
      const auto& v = required(f.particleVelocities, n, "particle velocities");
      for (size_t i = 0; i < n; ++i) out[i] = v[i].y();
      break;
    }
    case ParticleQuantity::acceleration: {
      const auto& a = required(f.particleAccelerations, n, "particle accelerations");
      for (size_t i = 0; i < n; ++i) out[i] = a[i].norm();
      break;
    }
    case ParticleQuantity::kineticEnergy: {
      const auto& v = required(f.particleVelocities, n, "particle velocities");
      const auto& m = required(f.particleMasses, n, "particle masses");
      for (size_t i = 0; i < n; ++i) out[i] = 0.5 * m[i] * v[i].squaredNorm();
      break;
    }
    case ParticleQuantity::height:
      for (size_t i = 0; i < n; ++i) out[i] = f.particles[i].y();
      break;
    case ParticleQuantity::mass: {
      const auto& m = required(f.particleMasses, n, "particle masses");
      std::copy(m.begin(), m.end(), out.begin());
      break;
    }
  }
}

void springValues(const Drawing& f, SpringQuantity q, std::vector<double>& out) {
  // Each spring's (length, rest, ks): by position, then by index as System::draw defines them.
  const size_t byPosition = f.springs.size(), byIndex = f.springsByIndex();
  out.resize(byPosition + byIndex);
  auto value = [q](double length, double rest, double ks) {
    const double stretch = length - rest;
    switch (q) {
      case SpringQuantity::strain: return rest > 0.0 ? length / rest - 1.0 : 0.0;
      case SpringQuantity::tension: return ks * stretch;
      case SpringQuantity::energy: return 0.5 * ks * stretch * stretch;
    }
    return 0.0;
  };
  for (size_t i = 0; i < byPosition; ++i) {
    const Drawing::Spring& s = f.springs[i];
    // Strain as the spring kind computed it (the same bits as without a style).
    out[i] = q == SpringQuantity::strain ? s.strain : value((s.a - s.b).norm(), s.rest, s.stiffness);
  }
  if (byIndex == 0) return;
  const Drawing::SpringTopology& t = *f.springTopology;
  const bool stiffnessKnown = t.stiffness.size() == byIndex;
  if (q != SpringQuantity::strain && !stiffnessKnown) {
    throw std::invalid_argument("the drawing's spring topology lacks the springs' stiffness");
  }
  for (size_t k = 0; k < byIndex; ++k) {
    const std::uint32_t a = t.ends[2 * k], b = t.ends[2 * k + 1];
    if (a >= f.particles.size() || b >= f.particles.size()) {
      throw std::invalid_argument("a spring of the drawing's topology ends past its particles");
    }
    out[byPosition + k] =
        value((f.particles[a] - f.particles[b]).norm(), t.rest[k], stiffnessKnown ? t.stiffness[k] : 0.0);
  }
}

void bodyValues(const Drawing& f, BodyQuantity q, std::vector<double>& out) {
  const size_t n = f.bodies.size();
  out.resize(n);
  if (q == BodyQuantity::speed) {
    const auto& v = required(f.bodyVelocities, n, "body velocities");
    for (size_t j = 0; j < n; ++j) out[j] = v[j].norm();
  } else {
    const auto& w = required(f.bodyAngularVelocities, n, "body angular velocities");
    for (size_t j = 0; j < n; ++j) out[j] = std::abs(w[j]);
  }
}

void ValueRange::add(const std::vector<double>& values, bool positiveOnly) {
  for (double v : values) {
    if (!std::isfinite(v) || (positiveOnly && !(v > 0.0))) continue;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
}

void ValueRange::add(const ValueRange& other) {
  lo = std::min(lo, other.lo);
  hi = std::max(hi, other.hi);
}

double ColorScale::position(double value) const {
  double t;
  if (logScale) {
    if (!(value > 0.0)) return 0.0;
    t = (std::log10(value) - std::log10(lo)) / (std::log10(hi) - std::log10(lo));
  } else {
    t = (value - lo) / (hi - lo);
  }
  if (std::isnan(t)) return 0.0;
  return std::clamp(t, 0.0, 1.0);
}

ColorScale scaleOf(const Range& range, const ValueRange& seen) {
  if (!range.automatic) return {range.lo, range.hi, range.logScale};
  if (seen.empty()) return range.logScale ? ColorScale{0.1, 10.0, true} : ColorScale{0.0, 1.0, false};
  if (seen.lo < seen.hi) return {seen.lo, seen.hi, range.logScale};
  const double v = seen.lo;
  if (range.logScale) return {v / 10.0, v * 10.0, true};
  if (v == 0.0) return {-1.0, 1.0, false};
  const double half = 0.5 * std::abs(v);
  return {v - half, v + half, false};
}

Range effectiveRange(const SpringStyle& springs) {
  if (springs.rangeGiven || springs.colorBy == SpringQuantity::strain) return springs.range;
  Range automatic;
  automatic.logScale = springs.range.logScale;
  return automatic;
}

bool StyleRanges::needed(const Style& s) {
  return (s.particles.colorBy && s.particles.range.automatic) ||
         (!s.springs.color && effectiveRange(s.springs).automatic) || (s.bodies.colorBy && s.bodies.range.automatic);
}

void StyleRanges::add(const Drawing& frame) {
  const Style& s = style_;
  if (s.particles.colorBy && s.particles.range.automatic) {
    particleValues(frame, *s.particles.colorBy, values_);
    particles_.add(values_, s.particles.range.logScale);
  }
  if (!s.springs.color && effectiveRange(s.springs).automatic) {
    springValues(frame, s.springs.colorBy, values_);
    springs_.add(values_, s.springs.range.logScale);
  }
  if (s.bodies.colorBy && s.bodies.range.automatic) {
    bodyValues(frame, *s.bodies.colorBy, values_);
    bodies_.add(values_, s.bodies.range.logScale);
  }
}

}  // namespace particles::style
