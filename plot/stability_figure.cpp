#include "plot/stability_figure.hpp"

#include <algorithm>
#include <optional>

namespace particles::plot {

Figure stabilityFigure(const std::vector<StabilityRow>& rows, const StabilityFigureNotes& notes) {
  DotChart chart;
  chart.xLabel = "dt [s]";
  DotGroup stable{"largest stable dt", {}}, smooth{"largest dt without shaking", {}};
  bool anyReference = false;
  for (const StabilityRow& row : rows) {
    chart.categories.push_back(row.integrator);
    stable.values.push_back(row.maxStableDt);
    smooth.values.push_back(row.maxSmoothDt);
    stable.lowerBounds.push_back(row.stableAtMaxDt);
    smooth.lowerBounds.push_back(row.smoothAtMaxDt);
    const auto found = notes.references.find(row.integrator);
    chart.references.push_back(found == notes.references.end() ? std::nullopt : std::optional(found->second));
    anyReference = anyReference || found != notes.references.end();
  }
  if (!anyReference) chart.references.clear();
  chart.referenceName = notes.referenceName;
  chart.groups = {std::move(stable), std::move(smooth)};
  Figure figure;
  figure.title = notes.scenario.empty() ? "Largest time step per integrator"
                                        : "Largest time step per integrator: " + notes.scenario;
  figure.caption = notes.caption;
  figure.chart = std::move(chart);
  figure.heightPx =
      std::max(360, 170 + 60 * static_cast<int>(rows.size()) + 18 * static_cast<int>(notes.caption.size()));
  return figure;
}

}  // namespace particles::plot
