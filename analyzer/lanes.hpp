// Doubles in vector lanes, one value a lane, through the vector extensions GCC and Clang share:
// two lanes (128 bits, SSE2, any x86-64) or four (256 bits, AVX2), and the few element-wise
// operations that formulas written once for a double and for lanes need.
//
// Why vector extensions and not intrinsics: the curvature face pass is compiled twice, for any
// x86-64 with two lanes and for AVX2 with fused multiply-adds with four (curvature.cpp). The
// same source becomes native vector instructions in both, and every lane computes exactly what
// the scalar formula computes (no arithmetic mixes lanes; only the transposes below move values
// between them).
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

using Lanes2 = double __attribute__((vector_size(16)));
using Lanes4 = double __attribute__((vector_size(32)));
using LaneMask2 = std::int64_t __attribute__((vector_size(16)));  // all ones where true
using LaneMask4 = std::int64_t __attribute__((vector_size(32)));

// Lanes in a value type: 1 for a double.
template <class Real>
inline constexpr int lanes_of = static_cast<int>(sizeof(Real) / sizeof(double));

// The mask type of comparisons of Real: bool, or an integer vector of Real's width.
template <class Real>
using MaskOf = decltype(Real{} < Real{});

// Real's bits as unsigned integers of its width (shifts of them are logical).
using LaneBits2 = std::uint64_t __attribute__((vector_size(16)));
using LaneBits4 = std::uint64_t __attribute__((vector_size(32)));
template <class Real>
using BitsOf =
    std::conditional_t<std::is_same_v<Real, double>, std::uint64_t,
                       std::conditional_t<std::is_same_v<Real, Lanes2>, LaneBits2, LaneBits4>>;

// A value in every lane (for a double, the value).
template <class Real>
[[gnu::always_inline]] inline Real splat(double value) {
  if constexpr (std::is_same_v<Real, double>) {
    return value;
  } else {
    Real lanes;
    for (int lane = 0; lane < lanes_of<Real>; ++lane) lanes[lane] = value;
    return lanes;
  }
}

template <class Mask, class Real>
[[gnu::always_inline]] inline Real select(Mask condition, Real if_true, Real if_false) {
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
template <class Real>
[[gnu::always_inline]] inline Real absolute(Real x) {
  if constexpr (std::is_same_v<Real, double>) {
    return std::abs(x);
  } else {
    const MaskOf<Real> magnitude_bits = std::bit_cast<MaskOf<Real>>(x) & 0x7fffffffffffffff;
    return std::bit_cast<Real>(magnitude_bits);
  }
}

// Correctly rounded in each lane (the compiler makes one vector square root of the lanes with
// -fno-math-errno, which curvature.cpp is built with).
template <class Real>
[[gnu::always_inline]] inline Real square_root(Real x) {
  if constexpr (std::is_same_v<Real, double>) {
    return std::sqrt(x);
  } else {
    Real root;
    for (int lane = 0; lane < lanes_of<Real>; ++lane) root[lane] = __builtin_sqrt(x[lane]);
    return root;
  }
}

// a · b of two three-element vectors given by their coordinates.
template <class Real>
[[gnu::always_inline]] inline Real dot3(const Real* a, const Real* b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Lanes from and to memory that need not be aligned.
template <class Real>
[[gnu::always_inline]] inline Real load_lanes(const double* values) {
  Real lanes;
  std::memcpy(&lanes, values, sizeof lanes);
  return lanes;
}
template <class Real>
[[gnu::always_inline]] inline void store_lanes(double* values, Real lanes) {
  std::memcpy(values, &lanes, sizeof lanes);
}
template <class Mask>
[[gnu::always_inline]] inline void store_mask(std::int64_t* values, Mask mask) {
  std::memcpy(values, &mask, sizeof mask);
}

// Four quantities of a lane's worth of items (rows[q][item]) stored item by item as records of
// four doubles (records[item][q]): a transpose.
[[gnu::always_inline]] inline void store_records(double (*records)[4], const Lanes4 (&rows)[4]) {
  const Lanes4 ab_even = __builtin_shufflevector(rows[0], rows[1], 0, 4, 2, 6);
  const Lanes4 ab_odd = __builtin_shufflevector(rows[0], rows[1], 1, 5, 3, 7);
  const Lanes4 cd_even = __builtin_shufflevector(rows[2], rows[3], 0, 4, 2, 6);
  const Lanes4 cd_odd = __builtin_shufflevector(rows[2], rows[3], 1, 5, 3, 7);
  store_lanes(records[0], __builtin_shufflevector(ab_even, cd_even, 0, 1, 4, 5));
  store_lanes(records[1], __builtin_shufflevector(ab_odd, cd_odd, 0, 1, 4, 5));
  store_lanes(records[2], __builtin_shufflevector(ab_even, cd_even, 2, 3, 6, 7));
  store_lanes(records[3], __builtin_shufflevector(ab_odd, cd_odd, 2, 3, 6, 7));
}
[[gnu::always_inline]] inline void store_records(double (*records)[4], const Lanes2 (&rows)[4]) {
  store_lanes(records[0], __builtin_shufflevector(rows[0], rows[1], 0, 2));
  store_lanes(records[0] + 2, __builtin_shufflevector(rows[2], rows[3], 0, 2));
  store_lanes(records[1], __builtin_shufflevector(rows[0], rows[1], 1, 3));
  store_lanes(records[1] + 2, __builtin_shufflevector(rows[2], rows[3], 1, 3));
}

// Two quantities of a lane's worth of items stored as pairs {a[item], b[item]}.
[[gnu::always_inline]] inline void store_pairs(double (*pairs)[2], Lanes4 a, Lanes4 b) {
  store_lanes(pairs[0], __builtin_shufflevector(a, b, 0, 4, 1, 5));
  store_lanes(pairs[2], __builtin_shufflevector(a, b, 2, 6, 3, 7));
}
[[gnu::always_inline]] inline void store_pairs(double (*pairs)[2], Lanes2 a, Lanes2 b) {
  store_lanes(pairs[0], __builtin_shufflevector(a, b, 0, 2));
  store_lanes(pairs[1], __builtin_shufflevector(a, b, 1, 3));
}

}  // namespace toonwater

#pragma GCC diagnostic pop
