#pragma once
// The hot loop of DampedSpringForce between particles: f_a of each spring in a range,
//   f_a = −[k_s (|l| − r) |l| + k_d l̇·l] / |l|² · l,   l = x_a − x_b,   0 when |l| < 1e-12 m
// (docs/physics.md §4, with |f|/|l| over one division). Four springs at a time with AVX2 where
// the processor has it, one at a time otherwise.
//
// The two loops give the same bits: each spring's numbers go through the same IEEE operations in
// the same order (sub, mul, add, sqrt, div; no fused multiply-add: the core is compiled with
// -ffp-contract=off and the AVX2 code enables no FMA), and packed operations round each lane as
// the scalar ones do. So the choice, made once per process from the CPU, changes no result;
// tests/test_spring_force_kernel.cpp compares the two bit for bit.

#include <cstddef>

namespace particles {

constexpr double kMinSpringLength = 1e-12;  // m; below this l/|l| is undefined and f = 0

struct SpringArrays {
  const int* endA;  // 2 · particle index of each spring's a end (its x in a [x0 y0 x1 y1 …] block)
  const int* endB;
  const double* rest;
  const double* ks;
  const double* kd;
};

// Writes (f_a, f_b = −f_a) of springs [begin, end) to out[4(i − begin) … 4(i − begin) + 3]; x and
// v are the positions and velocities, 2 per particle.
void springForcesScalar(const SpringArrays& springs, const double* x, const double* v, double* out, size_t begin,
                        size_t end);
// The same, four springs per step; false (and nothing written) where the CPU lacks AVX2 or the
// build is not for x86-64.
bool springForcesAvx2(const SpringArrays& springs, const double* x, const double* v, double* out, size_t begin,
                      size_t end);
// The AVX2 loop where it runs, else the scalar one.
void springForces(const SpringArrays& springs, const double* x, const double* v, double* out, size_t begin, size_t end);

}  // namespace particles
