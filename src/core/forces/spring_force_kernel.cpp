#include "core/forces/spring_force_kernel.hpp"

#include <cmath>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace particles {

namespace {

#if defined(__x86_64__)
// (x, y) at base + first and at base + second, in the two 128-bit lanes.
__attribute__((target("avx2"))) inline __m256d loadPairs(const double* base, int first, int second) {
  return _mm256_set_m128d(_mm_loadu_pd(base + second), _mm_loadu_pd(base + first));
}

// Springs [begin, begin + 4k); the caller finishes the remainder with the scalar loop.
__attribute__((target("avx2"))) size_t springForcesAvx2Body(const SpringArrays& s, const double* x, const double* v,
                                                            double* out, size_t begin, size_t end) {
  const __m256d minLength = _mm256_set1_pd(kMinSpringLength);
  const __m256d signBit = _mm256_set1_pd(-0.0);
  size_t i = begin;
  for (; i + 4 <= end; i += 4) {
    const int a0 = s.endA[i], a1 = s.endA[i + 1], a2 = s.endA[i + 2], a3 = s.endA[i + 3];
    const int b0 = s.endB[i], b1 = s.endB[i + 1], b2 = s.endB[i + 2], b3 = s.endB[i + 3];
    // l and l̇ as [x0 y0 | x2 y2] and [x1 y1 | x3 y3], then per coordinate: [s0 s1 | s2 s3].
    const __m256d l02 = _mm256_sub_pd(loadPairs(x, a0, a2), loadPairs(x, b0, b2));
    const __m256d l13 = _mm256_sub_pd(loadPairs(x, a1, a3), loadPairs(x, b1, b3));
    const __m256d d02 = _mm256_sub_pd(loadPairs(v, a0, a2), loadPairs(v, b0, b2));
    const __m256d d13 = _mm256_sub_pd(loadPairs(v, a1, a3), loadPairs(v, b1, b3));
    const __m256d lx = _mm256_unpacklo_pd(l02, l13), ly = _mm256_unpackhi_pd(l02, l13);
    const __m256d dx = _mm256_unpacklo_pd(d02, d13), dy = _mm256_unpackhi_pd(d02, d13);
    const __m256d len2 = _mm256_add_pd(_mm256_mul_pd(lx, lx), _mm256_mul_pd(ly, ly));
    const __m256d len = _mm256_sqrt_pd(len2);
    const __m256d ldotl = _mm256_add_pd(_mm256_mul_pd(dx, lx), _mm256_mul_pd(dy, ly));
    const __m256d ks = _mm256_loadu_pd(s.ks + i), rest = _mm256_loadu_pd(s.rest + i), kd = _mm256_loadu_pd(s.kd + i);
    const __m256d numerator =
        _mm256_add_pd(_mm256_mul_pd(_mm256_mul_pd(ks, _mm256_sub_pd(len, rest)), len), _mm256_mul_pd(kd, ldotl));
    // mag = 0 where |l| < kMinSpringLength (or NaN), as the scalar branch.
    const __m256d mag = _mm256_and_pd(_mm256_div_pd(numerator, len2), _mm256_cmp_pd(len, minLength, _CMP_GE_OQ));
    const __m256d negMag = _mm256_xor_pd(mag, signBit);  // −mag, exactly
    const __m256d fx = _mm256_mul_pd(negMag, lx), fy = _mm256_mul_pd(negMag, ly);
    // [fx0 fy0 | fx2 fy2] and [fx1 fy1 | fx3 fy3]; each spring's (f_a, −f_a) is one 256-bit store.
    const __m256d f02 = _mm256_unpacklo_pd(fx, fy), f13 = _mm256_unpackhi_pd(fx, fy);
    const __m256d f00 = _mm256_permute2f128_pd(f02, f02, 0x00), f22 = _mm256_permute2f128_pd(f02, f02, 0x11);
    const __m256d f11 = _mm256_permute2f128_pd(f13, f13, 0x00), f33 = _mm256_permute2f128_pd(f13, f13, 0x11);
    const __m256d negateHigh = _mm256_set_pd(-0.0, -0.0, 0.0, 0.0);
    double* at = out + 4 * (i - begin);
    _mm256_storeu_pd(at, _mm256_xor_pd(f00, negateHigh));
    _mm256_storeu_pd(at + 4, _mm256_xor_pd(f11, negateHigh));
    _mm256_storeu_pd(at + 8, _mm256_xor_pd(f22, negateHigh));
    _mm256_storeu_pd(at + 12, _mm256_xor_pd(f33, negateHigh));
  }
  return i;
}

bool cpuHasAvx2() {
  static const bool has = __builtin_cpu_supports("avx2");
  return has;
}
#endif

}  // namespace

void springForcesScalar(const SpringArrays& s, const double* x, const double* v, double* out, size_t begin,
                        size_t end) {
  for (size_t i = begin; i < end; ++i) {
    const int ia = s.endA[i], ib = s.endB[i];
    const double lx = x[ia] - x[ib], ly = x[ia + 1] - x[ib + 1];
    const double len2 = lx * lx + ly * ly;
    const double len = std::sqrt(len2);
    // |f| / |l| = [k_s (|l| − r) + k_d (l̇·l)/|l|] / |l| = [k_s (|l| − r) |l| + k_d l̇·l] / |l|²: one division
    double mag = 0.0;
    if (len >= kMinSpringLength) {
      const double ldotl = (v[ia] - v[ib]) * lx + (v[ia + 1] - v[ib + 1]) * ly;
      mag = (s.ks[i] * (len - s.rest[i]) * len + s.kd[i] * ldotl) / len2;
    }
    const double fx = -mag * lx, fy = -mag * ly;
    double* at = out + 4 * (i - begin);
    at[0] = fx;
    at[1] = fy;
    at[2] = -fx;
    at[3] = -fy;
  }
}

bool springForcesAvx2([[maybe_unused]] const SpringArrays& s, [[maybe_unused]] const double* x,
                      [[maybe_unused]] const double* v, [[maybe_unused]] double* out, [[maybe_unused]] size_t begin,
                      [[maybe_unused]] size_t end) {
#if defined(__x86_64__)
  if (!cpuHasAvx2()) return false;
  const size_t done = springForcesAvx2Body(s, x, v, out, begin, end);
  springForcesScalar(s, x, v, out + 4 * (done - begin), done, end);
  return true;
#else
  return false;
#endif
}

void springForces(const SpringArrays& s, const double* x, const double* v, double* out, size_t begin, size_t end) {
  if (!springForcesAvx2(s, x, v, out, begin, end)) springForcesScalar(s, x, v, out, begin, end);
}

}  // namespace particles
