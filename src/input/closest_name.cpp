#include "input/closest_name.hpp"

#include <algorithm>
#include <cctype>

namespace particles::input {

size_t editDistance(std::string_view a, std::string_view b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const size_t cost = std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + cost});
      diagonal = up;
    }
  }
  return row[b.size()];
}

namespace {

// editDistance(a, b) when it is below `bound`, else `bound` or more: only the band of cells within
// bound − 1 of the diagonal can hold a smaller distance, and the rows stop once every cell of one
// reaches the bound. A name of 2,000 letters against 100,000 short ones is then refused by its
// length alone, instead of 2,000 × 12 cells for each (bench/README.md, "Measurements behind
// choices in the source").
size_t editDistanceBelow(std::string_view a, std::string_view b, size_t bound) {
  const size_t longer = std::max(a.size(), b.size()), shorter = std::min(a.size(), b.size());
  if (longer - shorter >= bound) return bound;
  const size_t outside = bound;  // any value ≥ bound stands for "too far"
  std::vector<size_t> row(b.size() + 1, outside);
  for (size_t j = 0; j <= std::min(b.size(), bound); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    const size_t from = i >= bound ? i - bound + 1 : 1, to = std::min(b.size(), i + bound - 1);
    size_t diagonal = from >= 2 ? row[from - 1] : row[0];
    if (from == 1) {
      diagonal = row[0];
      row[0] = i < bound ? i : outside;
    } else {
      row[from - 1] = outside;
    }
    size_t best = row[0];
    for (size_t j = from; j <= to; ++j) {
      const size_t up = row[j];
      const size_t cost = std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ? 0 : 1;
      row[j] = std::min({up + 1, row[j - 1] + 1, diagonal + cost, outside});
      diagonal = up;
      best = std::min(best, row[j]);
    }
    if (to < b.size()) row[to + 1] = outside;
    if (best >= bound) return bound;
  }
  return std::min(row[b.size()], outside);
}

}  // namespace

std::string closestName(std::string_view word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t bestDistance = std::max<size_t>(2, word.size() / 3) + 1;  // at most a third of the word wrong
  for (const std::string& c : candidates) {
    const size_t d = editDistanceBelow(word, c, bestDistance);
    if (d < bestDistance) {
      bestDistance = d;
      best = c;
    }
  }
  return best;
}

}  // namespace particles::input
