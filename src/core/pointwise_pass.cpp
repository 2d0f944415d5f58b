#include "core/pointwise_pass.hpp"

namespace particles {

bool PointwiseRun::collect(std::span<const std::unique_ptr<Force>> forces) {
  gathers_.clear();
  linears_.clear();
  for (const auto& force : forces) {
    const PointwiseTerm term = force->pointwiseTerm();
    switch (term.kind) {
      case PointwiseTerm::Kind::none: return false;
      case PointwiseTerm::Kind::gather:
        if (!linears_.empty()) return false;
        gathers_.push_back(term);
        break;
      case PointwiseTerm::Kind::perMass:
      case PointwiseTerm::Kind::perVelocity: linears_.push_back(term); break;
    }
  }
  return true;
}

namespace {

template <bool kClear, bool kDerive>
void runPoints(const std::vector<PointwiseTerm>& gathers, const std::vector<GatherValues>& values,
               const std::vector<PointwiseTerm>& linears, const PointwiseRun::Points& p, int begin, int end) {
  const size_t gatherCount = gathers.size();
  const PointwiseTerm* linearBegin = linears.data();
  const PointwiseTerm* linearEnd = linearBegin + linears.size();
  for (int i = begin; i < end; ++i) {
    double fx = kClear ? 0.0 : p.force[2 * i];
    double fy = kClear ? 0.0 : p.force[2 * i + 1];
    for (size_t g = 0; g < gatherCount; ++g) {
      const int* start = gathers[g].start;
      const int* entries = values[g].entries;
      const double* chunkValues = values[g].values;
      for (int k = start[i]; k < start[i + 1]; ++k) {
        const double* value = chunkValues + entries[k];
        fx += value[0];
        fy += value[1];
      }
    }
    const double vx = p.velocity[2 * i], vy = p.velocity[2 * i + 1];
    for (const PointwiseTerm* l = linearBegin; l != linearEnd; ++l) {
      if (l->kind == PointwiseTerm::Kind::perMass) {
        fx += p.mass[i] * l->a.x();
        fy += p.mass[i] * l->a.y();
      } else {
        fx -= l->c * vx;
        fy -= l->c * vy;
      }
    }
    p.force[2 * i] = fx;
    p.force[2 * i + 1] = fy;
    if constexpr (kDerive) {
      p.derivative[2 * i] = vx;
      p.derivative[2 * i + 1] = vy;
      p.derivative[p.velocityRow + 2 * i] = fx * p.invMass[i];
      p.derivative[p.velocityRow + 2 * i + 1] = fy * p.invMass[i];
    }
  }
}

}  // namespace

void PointwiseRun::run(const Points& points, int begin, int end, bool clear) const {
  // The gathered terms' values for this chunk, computed on this thread into its own scratch.
  thread_local std::vector<std::vector<double>> scratch;
  thread_local std::vector<GatherValues> values;
  if (scratch.size() < gathers_.size()) scratch.resize(gathers_.size());
  values.resize(gathers_.size());
  for (size_t g = 0; g < gathers_.size(); ++g) values[g] = gathers_[g].source->valuesFor(begin, end, scratch[g]);
  const bool derive = points.derivative != nullptr;
  if (clear && derive) {
    runPoints<true, true>(gathers_, values, linears_, points, begin, end);
  } else if (clear) {
    runPoints<true, false>(gathers_, values, linears_, points, begin, end);
  } else if (derive) {
    runPoints<false, true>(gathers_, values, linears_, points, begin, end);
  } else {
    runPoints<false, false>(gathers_, values, linears_, points, begin, end);
  }
}

}  // namespace particles
