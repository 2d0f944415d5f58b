#include "plot/column_reduction.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace particles::plot {

std::vector<Point> reduceToColumns(const std::vector<Point>& run, double columnWidthPx) {
  if (run.size() <= 4 || !(columnWidthPx > 0)) return run;
  std::vector<Point> out;
  std::size_t start = 0;
  while (start < run.size()) {
    const double column = std::floor(run[start].x / columnWidthPx);
    std::size_t end = start + 1, lowest = start, highest = start;
    while (end < run.size() && std::floor(run[end].x / columnWidthPx) == column) {
      if (run[end].y < run[lowest].y) lowest = end;
      if (run[end].y > run[highest].y) highest = end;
      ++end;
    }
    if (end - start <= 4) {
      out.insert(out.end(), run.begin() + std::ptrdiff_t(start), run.begin() + std::ptrdiff_t(end));
    } else {
      std::array<std::size_t, 4> kept = {start, lowest, highest, end - 1};
      std::sort(kept.begin(), kept.end());
      for (std::size_t k = 0; k < kept.size(); ++k) {
        if (k == 0 || kept[k] != kept[k - 1]) out.push_back(run[kept[k]]);
      }
    }
    start = end;
  }
  return out;
}

}  // namespace particles::plot
