#include "core/implicit_assembly.hpp"

#include "core/group_by_bucket.hpp"
#include "core/parallel_sparse.hpp"

namespace particles {

bool ImplicitAssembly::patternChanged() {
  const ForceJacobians& jac = w_.jacobians;
  const AssemblyPattern& pattern = w_.pattern;
  auto samePattern = [&](const ForceJacobians::Triplets& from, const std::vector<int>& keys) {
    if (2 * from.size() != keys.size()) return false;
    return !anyOf(pool_, from.size(), kRowChunk, w_.found,
                  [&](size_t k) { return ((from[k].row() ^ keys[2 * k]) | (from[k].col() ^ keys[2 * k + 1])) != 0; });
  };
  auto samePairs = [&] {
    const ForceJacobians::Pairs& pairs = jac.pairs;
    if (2 * pairs.size() != pattern.pairKeys.size()) return false;
    return !anyOf(pool_, pairs.size(), kRowChunk, w_.found, [&](size_t q) {
      return ((pairs[q].a ^ pattern.pairKeys[2 * q]) | (pairs[q].b ^ pattern.pairKeys[2 * q + 1])) != 0;
    });
  };
  return !pattern.valid || w_.matrix.rows() != n_ || pattern.pinned != w_.pinned ||
         !samePattern(jac.dfdv, pattern.dfdvKeys) || !samePattern(jac.dfdx, pattern.dfdxKeys) || !samePairs();
}

void ImplicitAssembly::buildMatrixPattern() {
  const ForceJacobians& jac = w_.jacobians;
  const ForceJacobians::Pairs& pairs = jac.pairs;
  AssemblyPattern& pattern = w_.pattern;
  w_.triplets.clear();
  w_.triplets.reserve(size_t(n_) + jac.dfdv.size() + jac.dfdx.size() + 16 * pairs.size());
  for (Eigen::Index i = 0; i < n_; ++i) w_.triplets.emplace_back(i, i, 1.0);
  pattern.pairKeys.clear();
  for (int q = 0; q < int(pairs.size()); ++q) {
    pattern.pairKeys.push_back(pairs[size_t(q)].a);
    pattern.pairKeys.push_back(pairs[size_t(q)].b);
    for (BlockRef::Role role : BlockRef::kRoles) {
      const auto [rowPoint, colPoint] = blockPoints({q, role});
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          if (!pinned(row) && !pinned(col)) w_.triplets.emplace_back(row, col, 1.0);
        }
      }
    }
  }
  auto keysOf = [&](const ForceJacobians::Triplets& from, std::vector<int>& keys) {
    keys.clear();
    for (const auto& e : from) {
      keys.push_back(e.row());
      keys.push_back(e.col());
      if (!pinned(e.row()) && !pinned(e.col())) w_.triplets.emplace_back(e.row(), e.col(), 1.0);
    }
  };
  keysOf(jac.dfdv, pattern.dfdvKeys);
  keysOf(jac.dfdx, pattern.dfdxKeys);
  pattern.pinned = w_.pinned;
  w_.matrix.resize(n_, n_);
  w_.matrix.setFromTriplets(w_.triplets.begin(), w_.triplets.end());
  w_.matrix.makeCompressed();
}

void ImplicitAssembly::mapTripletSlots() {
  const ForceJacobians& jac = w_.jacobians;
  AssemblyPattern& pattern = w_.pattern;
  // Each triplet's slot (−1: a pinned coordinate's, left out), and those in a free row and an
  // eliminated column.
  std::vector<int> slotOfEntry;
  slotOfEntry.reserve(jac.dfdv.size() + jac.dfdx.size());
  pattern.pinnedColumnEntries.clear();
  auto slotsOf = [&](const ForceJacobians::Triplets& from, int firstEntry) {
    for (size_t k = 0; k < from.size(); ++k) {
      const auto& e = from[k];
      const bool out = pinned(e.row()) || pinned(e.col());
      slotOfEntry.push_back(out ? -1 : slotOf(e.row(), e.col()));
      if (!pinned(e.row()) && pinned(e.col()) && !fixedDof(e.col())) {
        pattern.pinnedColumnEntries.push_back(firstEntry + int(k));
      }
    }
  };
  slotsOf(jac.dfdv, 0);
  slotsOf(jac.dfdx, int(jac.dfdv.size()));
  // The reverse maps (see AssemblyPattern), by counting sorts that keep the triplets' order.
  const size_t slots = size_t(w_.matrix.nonZeros());
  pattern.slotDiagonal.assign(slots, -1);
  for (Eigen::Index i = 0; i < n_; ++i) pattern.slotDiagonal[size_t(slotOf(i, i))] = int(i);
  groupByBucket(slots, slotOfEntry, pattern.slotStart, pattern.slotEntries);
  std::vector<int> rowOfEntry;
  rowOfEntry.reserve(jac.dfdx.size());
  for (const auto& e : jac.dfdx) rowOfEntry.push_back(int(e.row()));
  groupByBucket(size_t(n_), rowOfEntry, pattern.kRowStart, pattern.kRowEntries);
}

void ImplicitAssembly::mapPairBlocks() {
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  AssemblyPattern& pattern = w_.pattern;
  // Every pair's four blocks in the pairs' order, each found by its first slot that is not pinned
  // out, then grouped by that slot: the references of one block of A, in the pairs' order.
  std::vector<BlockRef> refs;
  refs.reserve(4 * pairs.size());
  std::vector<int> leadSlotOfRef(4 * pairs.size(), -1), blockStart, grouped;
  pattern.pinnedPairEntries.clear();
  for (int q = 0; q < int(pairs.size()); ++q) {
    for (BlockRef::Role role : BlockRef::kRoles) {
      const BlockRef ref{q, role};
      int slot[4];
      slotsOfBlock(ref, slot);
      for (int s : slot) {
        if (s >= 0) {
          leadSlotOfRef[refs.size()] = s;
          break;
        }
      }
      refs.push_back(ref);
      const auto [rowPoint, colPoint] = blockPoints(ref);
      for (int c = 0; c < 2; ++c) {
        for (int r = 0; r < 2; ++r) {
          const int row = 2 * rowPoint + r, col = 2 * colPoint + c;
          if (!pinned(row) && pinned(col) && !fixedDof(col)) pattern.pinnedPairEntries.push_back({ref, r, c});
        }
      }
    }
  }
  const size_t slots = size_t(w_.matrix.nonZeros());
  groupByBucket(slots, leadSlotOfRef, blockStart, grouped);
  pattern.pairBlockRefs.clear();
  for (int k : grouped) pattern.pairBlockRefs.push_back(refs[size_t(k)]);
  pattern.pairBlocks.clear();
  for (size_t slot = 0; slot < slots; ++slot) {
    if (blockStart[slot + 1] == blockStart[slot]) continue;
    AssemblyPattern::PairBlock block{};
    slotsOfBlock(pattern.pairBlockRefs[size_t(blockStart[slot])], block.slot);
    block.begin = blockStart[slot];
    block.end = blockStart[slot + 1];
    pattern.pairBlocks.push_back(block);
  }
}

void ImplicitAssembly::mapPairEnds() {
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  std::vector<int> pointOfEnd(2 * pairs.size());
  for (size_t q = 0; q < pairs.size(); ++q) {
    pointOfEnd[2 * q] = pairs[q].a;
    pointOfEnd[2 * q + 1] = pairs[q].b;
  }
  groupByBucket(size_t(n_ / 2), pointOfEnd, w_.pattern.pairPointStart, w_.pattern.pairPointRefs);
}

void ImplicitAssembly::fillMatrix(double eta) {
  const AssemblyPattern& pattern = w_.pattern;
  const ForceJacobians::Pairs& pairs = w_.jacobians.pairs;
  // Slot by slot: the diagonal's M (1 for a pinned coordinate), then −η D and −η² K in the
  // triplets' order.
  double* values = w_.matrix.valuePtr();
  forChunks(pool_, size_t(w_.matrix.nonZeros()), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t slot = begin; slot < end; ++slot) {
      const int diagonal = pattern.slotDiagonal[slot];
      double value = diagonal < 0 ? 0.0 : (pinned(diagonal) ? 1.0 : model_.mass[diagonal / 2]);
      for (int k = pattern.slotStart[slot]; k < pattern.slotStart[slot + 1]; ++k)
        value += entryValue(pattern.slotEntries[size_t(k)], eta);
      values[slot] = value;
    }
  });
  // Then the pairs' part, block by block: A's (a, a) and (b, b) blocks gain −η d − η² k, (a, b)
  // and (b, a) lose it.
  std::vector<double>& pairA = w_.pairA;
  pairA.resize(3 * pairs.size());
  forChunks(pool_, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      for (int j = 0; j < 3; ++j) pairA[3 * q + size_t(j)] = -eta * pairs[q].d[j] - eta * eta * pairs[q].k[j];
    }
  });
  forChunks(pool_, pattern.pairBlocks.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t b = begin; b < end; ++b) {
      const AssemblyPattern::PairBlock& block = pattern.pairBlocks[b];
      double sum[3] = {0.0, 0.0, 0.0};
      for (int k = block.begin; k < block.end; ++k) {
        const BlockRef ref = pattern.pairBlockRefs[size_t(k)];
        const double* m = &pairA[3 * size_t(ref.pair)];
        const double sign = ref.sign();
        for (int j = 0; j < 3; ++j) sum[j] += sign * m[j];
      }
      const double entry[4] = {sum[0], sum[1], sum[1], sum[2]};  // xx, yx, xy, yy
      for (int j = 0; j < 4; ++j) {
        if (block.slot[j] >= 0) values[block.slot[j]] += entry[j];
      }
    }
  });
}

void ImplicitAssembly::fillRightHandSide(const Eigen::VectorXd& y, double eta, const ImplicitTarget& target) {
  // b = M (v̄ − v_b) + η (f_b + K (x̄ − x_b + η v_b)), row by row; K's products straight from its
  // triplets, in their order, and from its pairs.
  const AssemblyPattern& pattern = w_.pattern;
  const ForceJacobians& jac = w_.jacobians;
  const ForceJacobians::Pairs& pairs = jac.pairs;
  const Eigen::Index vOff = model_.layout.velocityOffset();
  const Eigen::VectorXd* xShift = target.xShift;
  const Eigen::VectorXd* vShift = target.vShift;
  // A pair's K times that vector is k (u_a − u_b) at a and its negative at b.
  std::vector<double>& pairKu = w_.pairKu;
  pairKu.resize(2 * pairs.size());
  forChunks(pool_, pairs.size(), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t q = begin; q < end; ++q) {
      const int a = pairs[q].a, b = pairs[q].b;
      double u[2];
      for (int d = 0; d < 2; ++d) {
        u[d] = eta * (y[vOff + 2 * a + d] - y[vOff + 2 * b + d]);
        if (xShift) u[d] += (*xShift)[2 * a + d] - (*xShift)[2 * b + d];
      }
      const double* k = pairs[q].k;
      pairKu[2 * q] = k[0] * u[0] + k[1] * u[1];
      pairKu[2 * q + 1] = k[1] * u[0] + k[2] * u[1];
    }
  });
  w_.rhs.resize(n_);
  forChunks(pool_, size_t(n_), kRowChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      const double mass = model_.mass[Eigen::Index(i / 2)];
      double value = mass * w_.k1[vOff + Eigen::Index(i)];
      for (int k = pattern.kRowStart[i]; k < pattern.kRowStart[i + 1]; ++k) {
        const auto& e = jac.dfdx[size_t(pattern.kRowEntries[size_t(k)])];
        value += eta * e.value() * y[vOff + e.col()];
        if (xShift) value += e.value() * (*xShift)[e.col()];
      }
      for (int k = pattern.pairPointStart[i / 2]; k < pattern.pairPointStart[i / 2 + 1]; ++k) {
        const int ref = pattern.pairPointRefs[size_t(k)];
        const double ku = pairKu[2 * size_t(ref / 2) + i % 2];
        value += ref % 2 == 0 ? ku : -ku;
      }
      double b = eta * value;
      if (vShift) b += mass * (*vShift)[Eigen::Index(i)];
      w_.rhs[Eigen::Index(i)] = pinned(Eigen::Index(i)) ? 0.0 : b;
    }
  });
  // The eliminated coordinates' known Δv times their columns of A leaves the free rows' side.
  const int dCount = int(jac.dfdv.size());
  for (int entry : pattern.pinnedColumnEntries) {
    const auto& e = entry < dCount ? jac.dfdv[size_t(entry)] : jac.dfdx[size_t(entry - dCount)];
    w_.rhs[e.row()] -= entryValue(entry, eta) * w_.known[e.col()];
  }
  for (const auto& [ref, r, c] : pattern.pinnedPairEntries) {
    const auto [rowPoint, colPoint] = blockPoints(ref);
    const double* m = &w_.pairA[3 * size_t(ref.pair)];
    const double entry = ref.sign() * m[r + c];  // xx, xy = yx, yy
    w_.rhs[2 * rowPoint + r] -= entry * w_.known[2 * colPoint + c];
  }
}

}  // namespace particles
