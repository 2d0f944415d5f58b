#include "plot/stability_figure.hpp"

namespace particles::plot {

Figure stabilityFigure(const std::vector<StabilityRow>& rows) {
  BarChart chart;
  chart.xLabel = "integrator";
  chart.yLabel = "dt [s]";
  BarGroup stable{"largest stable dt", {}}, smooth{"largest dt without shaking", {}};
  for (const StabilityRow& row : rows) {
    chart.categories.push_back(row.integrator);
    stable.values.push_back(row.maxStableDt);
    smooth.values.push_back(row.maxSmoothDt);
  }
  chart.groups = {std::move(stable), std::move(smooth)};
  Figure figure;
  figure.title = "Largest time step per integrator";
  figure.chart = std::move(chart);
  return figure;
}

}  // namespace particles::plot
