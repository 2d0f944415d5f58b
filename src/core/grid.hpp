#pragma once
// A rectangular grid of particles joined by springs: the cloth and soft-body building block.
// Row 0 is on top at `origin`; row r lies at origin.y − r·spacing.y, column c at
// origin.x + c·spacing.x. Spring families (any may be absent):
//   structural  neighbours along rows and columns      rows·(cols−1) + (rows−1)·cols springs
//   shear       both diagonals of every cell           2·(rows−1)·(cols−1)
//   flexion     every second particle along rows/cols  rows·(cols−2) + (rows−2)·cols
// Stiffness may vary linearly with height, from ksTop at row 0 to ksBottom at the last row, taken
// at the spring's mid-height (the report's cloth: 25 at the top to 1 at the bottom).

#include <optional>
#include <string>

#include "core/forces/damped_spring_force.hpp"
#include "core/system.hpp"

namespace particles {

struct GridSpringFamily {
  double ksTop;
  double ksBottom;
  double kd;
};

struct GridSpec {
  std::string name;
  Vec2 origin = Vec2::Zero();
  int cols = 1;
  int rows = 1;
  Vec2 spacing = Vec2(0.1, 0.1);
  double mass = 1.0;  // per particle
  std::optional<GridSpringFamily> structural, shear, flexion;
};

struct GridIndices {
  int first = 0;  // particle index of row 0, column 0
  int cols = 0;
  int rows = 0;
  int at(int row, int col) const { return first + row * cols + col; }
};

// Adds the particles (named "name[row][col]") to the builder and the springs to `springs`.
GridIndices addGrid(SystemBuilder& builder, DampedSpringForce& springs, const GridSpec& spec);
// How many springs addGrid adds for `spec`, without adding them (for the loader's budgets).
long long gridSpringCount(const GridSpec& spec);

}  // namespace particles
