// Four doubles a vector, one value a lane, through GCC's vector extensions, and the few
// element-wise operations that formulas written once for a double and for four lanes need.
//
// Why vector extensions and not intrinsics: the curvature face pass is compiled twice, for any
// x86-64 and for AVX2 with fused multiply-adds (curvature.cpp). The same source becomes two
// 128-bit operations a step in the first and one 256-bit operation in the second, and every lane
// computes exactly what the scalar formula computes (no operation mixes lanes).
//
// Each helper also takes plain doubles and then does what the standard library does
// (std::min, std::max, std::abs, std::sqrt, `?:`), so a formula written as a template over the
// value type gives the same bits for a double and for each lane.
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

// GCC notes that a function taking 256-bit vectors passes them differently where AVX is off:
// these are all inlined, so no call passes them at all.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

namespace toonwater {

using Lanes = double __attribute__((vector_size(32)));
using LaneMask = std::int64_t __attribute__((vector_size(32)));  // all ones where true
inline constexpr int lane_count = 4;

// A value in every lane (for a double, the value).
template <class Real>
inline Real splat(double value) {
  if constexpr (std::is_same_v<Real, double>)
    return value;
  else
    return Real{value, value, value, value};
}

inline double select(bool condition, double if_true, double if_false) {
  return condition ? if_true : if_false;
}
[[gnu::always_inline]] inline Lanes select(LaneMask condition, Lanes if_true, Lanes if_false) {
  return condition ? if_true : if_false;
}

// As std::min and std::max: the first argument when they compare equal (or either is NaN).
template <class Real>
[[gnu::always_inline]] inline Real minimum(Real a, Real b) {
  return select(b < a, b, a);
}
template <class Real>
[[gnu::always_inline]] inline Real maximum(Real a, Real b) {
  return select(a < b, b, a);
}

// |x| by clearing the sign bit, as std::abs does (−0 becomes +0, NaN stays NaN).
inline double absolute(double x) { return std::abs(x); }
[[gnu::always_inline]] inline Lanes absolute(Lanes x) {
  const LaneMask magnitude_bits = std::bit_cast<LaneMask>(x) & 0x7fffffffffffffff;
  return std::bit_cast<Lanes>(magnitude_bits);
}

// Correctly rounded in each lane (the compiler makes one vector square root of the four with
// -fno-math-errno, which curvature.cpp is built with).
inline double square_root(double x) { return std::sqrt(x); }
[[gnu::always_inline]] inline Lanes square_root(Lanes x) {
  Lanes root;
  for (int lane = 0; lane < lane_count; ++lane) root[lane] = __builtin_sqrt(x[lane]);
  return root;
}

// a · b of two three-element vectors given by their coordinates.
template <class Real>
[[gnu::always_inline]] inline Real dot3(const Real* a, const Real* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// The 4 × 4 transpose: lanes a, b, c, d become the first, second, third and fourth values of
// the four results (results[k] = {a[k], b[k], c[k], d[k]}).
[[gnu::always_inline]] inline void transpose(const Lanes (&rows)[4], Lanes (&columns)[4]) {
  const Lanes ab_even = __builtin_shuffle(rows[0], rows[1], LaneMask{0, 4, 2, 6});
  const Lanes ab_odd = __builtin_shuffle(rows[0], rows[1], LaneMask{1, 5, 3, 7});
  const Lanes cd_even = __builtin_shuffle(rows[2], rows[3], LaneMask{0, 4, 2, 6});
  const Lanes cd_odd = __builtin_shuffle(rows[2], rows[3], LaneMask{1, 5, 3, 7});
  columns[0] = __builtin_shuffle(ab_even, cd_even, LaneMask{0, 1, 4, 5});
  columns[1] = __builtin_shuffle(ab_odd, cd_odd, LaneMask{0, 1, 4, 5});
  columns[2] = __builtin_shuffle(ab_even, cd_even, LaneMask{2, 3, 6, 7});
  columns[3] = __builtin_shuffle(ab_odd, cd_odd, LaneMask{2, 3, 6, 7});
}

// a and b as four pairs {a[k], b[k]}: the first two in `low`, the last two in `high`.
[[gnu::always_inline]] inline void interleave(Lanes a, Lanes b, Lanes& low, Lanes& high) {
  low = __builtin_shuffle(a, b, LaneMask{0, 4, 1, 5});
  high = __builtin_shuffle(a, b, LaneMask{2, 6, 3, 7});
}

// Four consecutive doubles, from and to memory that need not be aligned.
[[gnu::always_inline]] inline Lanes load_lanes(const double* values) {
  Lanes lanes;
  std::memcpy(&lanes, values, sizeof lanes);
  return lanes;
}
[[gnu::always_inline]] inline void store_lanes(double* values, Lanes lanes) {
  std::memcpy(values, &lanes, sizeof lanes);
}
[[gnu::always_inline]] inline void store_mask(std::int64_t* values, LaneMask mask) {
  std::memcpy(values, &mask, sizeof mask);
}

}  // namespace toonwater

#pragma GCC diagnostic pop
