#pragma once
// The figure of the time-step stability study (`particles stability --plot`, docs/physics.md §12): per
// integrator, the largest stable dt and the largest dt without shaking, as dots on a log axis.

#include <map>
#include <string>
#include <vector>

#include "plot/figure.hpp"

namespace particles::plot {

// One row of `stability --csv`, whose header is
// integrator,evals_per_step,max_stable_dt,max_smooth_dt,evals_per_sim_second,speed_vs_euler
struct StabilityRow {
  std::string integrator;        // euler, midpoint, rk4, …
  int evalsPerStep = 0;          // derivative evaluations per step
  double maxStableDt = 0;        // [s]
  double maxSmoothDt = 0;        // [s], stable and not shaking
  double evalsPerSimSecond = 0;  // evalsPerStep / maxSmoothDt
  double speedVsEuler = 0;       // Euler's evalsPerSimSecond / this one's
  bool stableAtMaxDt = false;    // the search stopped at its largest dt: maxStableDt is a lower bound
  bool smoothAtMaxDt = false;    // the same for maxSmoothDt
};

// What the table does not say: the scenario (for the title), the criteria (the caption), and
// values to compare with, by integrator name (e.g. a report's own limits).
struct StabilityFigureNotes {
  std::string scenario;
  std::vector<std::string> caption;
  std::map<std::string, Reference> references;
  std::string referenceName = "reference";
};

// A dot plot, one row per integrator in the rows' order: the largest stable dt and the largest dt
// without shaking on a log axis fitted to them (and to the references); a dt ≤ 0 (nothing stable)
// shows as "n/a".
Figure stabilityFigure(const std::vector<StabilityRow>& rows, const StabilityFigureNotes& notes = {});

}  // namespace particles::plot
