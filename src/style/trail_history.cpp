#include "style/trail_history.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace particles::style {

TrailHistory::TrailHistory(const Style& style, double dt, long steps) {
  long long samples = 0;
  for (size_t k = 0; k < style.select.size(); ++k) {
    const Selection& sel = style.select[k];
    if (!sel.trail) continue;
    const TrailStyle& trail = *sel.trail;
    // Samples one trail holds at most: the steps in its window, plus the start and one in hand.
    const double window = std::min(double(steps), std::ceil(trail.seconds / dt));
    const long long perPoint = (std::isfinite(window) ? (long long)(window) : (long long)(steps)) + 2;
    const long long points = (long long)(sel.particles.size() + sel.bodies.size());
    if (points > 0 && perPoint > kMaxTrailSamples / points)
      samples = kMaxTrailSamples + 1;
    else
      samples += points * perPoint;
    if (samples > kMaxTrailSamples) {
      throw TrailLimitError("style.select[" + std::to_string(k) + "].trail: the trails would keep more than " +
                            std::to_string(kMaxTrailSamples) +
                            " positions at once (points × steps in their window); shorten trail.seconds or select "
                            "fewer points");
    }
    for (int i : sel.particles) trails_.push_back({i, -1, &trail, k, {}});
    for (int j : sel.bodies) trails_.push_back({-1, j, &trail, k, {}});
  }
}

void TrailHistory::record(const System& system) {
  const StateView s = system.view();
  const double t = system.time();
  for (Trail& trail : trails_) {
    const int point = trail.body >= 0 ? system.model().layout.bodyPoint(trail.body) : trail.particle;
    trail.samples.push_back({t, s.pos(point)});
    // Keep one sample older than the window, so that the trail reaches its full length.
    while (trail.samples.size() > 2 && trail.samples[1].t < t - trail.style->seconds) trail.samples.pop_front();
  }
}

}  // namespace particles::style
