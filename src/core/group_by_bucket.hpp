#pragma once
// A counting sort that the threaded passes use to turn a scatter into a gather: entry k belongs
// to bucket bucketOf[k] (or to none, −1); afterwards bucket b's entries are
// entries[start[b] … start[b+1]), in increasing order. A bucket (a particle, a matrix slot) can
// then sum its entries on one thread in the order a serial loop over the entries would have
// added them (springs' ends per particle, constraint rows per particle, backward Euler's
// triplets per value slot).

#include <cstddef>
#include <vector>

namespace particles {

inline void groupByBucket(size_t buckets, const std::vector<int>& bucketOf, std::vector<int>& start,
                          std::vector<int>& entries) {
  start.assign(buckets + 1, 0);
  for (int b : bucketOf) {
    if (b >= 0) ++start[size_t(b) + 1];
  }
  for (size_t b = 0; b < buckets; ++b) start[b + 1] += start[b];
  entries.resize(size_t(start[buckets]));
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (size_t k = 0; k < bucketOf.size(); ++k) {
    if (bucketOf[k] >= 0) entries[size_t(fill[size_t(bucketOf[k])]++)] = int(k);
  }
}

}  // namespace particles
