// ordered_sum: the blocks of a fixed size summed in index order, then the blocks' sums in block
// order, on values whose sum depends on the order of the additions, for lengths around the
// block size, and with terms left out (0) as a selection leaves them.
#include "common/ordered_sum.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

namespace toonwater {
namespace {

// The definition, on one thread.
double blockwise_sum(const std::vector<double>& values) {
  double total = 0.0;
  for (std::size_t block = 0; block * ordered_sum_block < values.size(); ++block) {
    double sum = 0.0;
    const std::size_t end = std::min(values.size(), (block + 1) * ordered_sum_block);
    for (std::size_t i = block * ordered_sum_block; i < end; ++i) sum += values[i];
    total += sum;
  }
  return total;
}

// Magnitudes over 30 orders, both signs: a different order of the additions gives other bits.
std::vector<double> spread_values(std::size_t n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-15, 15);
  std::vector<double> values(n);
  for (double& x : values) x = std::ldexp(mantissa(rng), exponent(rng));
  return values;
}

TEST(OrderedSums, AreTheBlocksSummedInOrder) {
  const std::size_t b = ordered_sum_block;
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, b - 1, b, b + 1, 5 * b + 123, 40 * b + 7}) {
    const std::vector<double> values = spread_values(n, static_cast<unsigned>(n));
    EXPECT_EQ(ordered_sum(n, [&](std::size_t i) { return values[i]; }), blockwise_sum(values))
        << "n = " << n;
  }
}

TEST(OrderedSums, DifferFromTheSerialSumOnlyByTheOrder) {
  // The test above could pass with any fixed order; this one checks that the order matters on
  // these values, so that it would catch another one.
  const std::vector<double> values = spread_values(40 * ordered_sum_block + 7, 9);
  double serial = 0.0;
  for (double x : values) serial += x;
  EXPECT_NE(serial, blockwise_sum(values));
}

TEST(OrderedSums, LeaveOutTheTermsASelectionSkips) {
  const std::size_t n = 3 * ordered_sum_block + 17;
  const std::vector<double> values = spread_values(n, 4);
  std::vector<double> odd(n, 0.0), even(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) (i % 2 ? odd : even)[i] = values[i];
  EXPECT_EQ(ordered_sum(n, [&](std::size_t i) { return i % 2 ? values[i] : 0.0; }), blockwise_sum(odd));
  EXPECT_EQ(ordered_sum(n, [&](std::size_t i) { return i % 2 ? 0.0 : values[i]; }), blockwise_sum(even));
}

}  // namespace
}  // namespace toonwater
