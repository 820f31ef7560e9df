// deterministic_sum: the same bits with any number of threads, on values whose sum changes
// with the order of addition; and within the error bound of recursive summation of the exact
// sum.
#include "common/deterministic_sum.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace toonwater {
namespace {

// Values of both signs spread over twelve orders of magnitude: a different order of additions
// gives a different rounding.
std::vector<double> spread_values(std::size_t n, std::uint64_t seed) {
  std::vector<double> values(n);
  std::uint64_t state = seed;
  for (double& v : values) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double unit = static_cast<double>(state >> 11) * 0x1p-53;
    v = (unit - 0.5) * std::pow(10.0, 12.0 * unit - 6.0);
  }
  return values;
}

double sum_with_threads(const std::vector<double>& values, int threads) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  return deterministic_sum(values.size(), [&](std::size_t i) { return values[i]; });
}

TEST(DeterministicSum, SameBitsWithOneTwoThreeAndFourThreads) {
  for (std::size_t n : {std::size_t{0}, std::size_t{1}, deterministic_sum_block - 1,
                        deterministic_sum_block + 1, 40 * deterministic_sum_block + 7}) {
    const std::vector<double> values = spread_values(n, n + 3);
    const double one = sum_with_threads(values, 1);
    for (int threads : {2, 3, 4})
      EXPECT_EQ(sum_with_threads(values, threads), one)
          << n << " values, " << threads << " threads";
  }
}

TEST(DeterministicSum, WithinTheRecursiveSummationBound) {
  const std::vector<double> values = spread_values(25 * deterministic_sum_block + 11, 7);
  long double exact = 0.0L, magnitude = 0.0L;
  for (double v : values) {
    exact += v;
    magnitude += std::abs(v);
  }
  // |error| ≤ (n − 1) ε Σ|x| for any order of additions (Higham, Accuracy and Stability, 4.2).
  const double bound = static_cast<double>(values.size()) * std::numeric_limits<double>::epsilon() *
                       static_cast<double>(magnitude);
  EXPECT_LE(std::abs(sum_with_threads(values, 2) - static_cast<double>(exact)), bound);
}

TEST(DeterministicSum, SumsTheTermOfEveryIndexOnce) {
  const std::size_t n = 3 * deterministic_sum_block + 17;
  // Integers are added exactly, so any index missed or repeated shows.
  const double sum = deterministic_sum(n, [](std::size_t i) { return static_cast<double>(i); });
  EXPECT_EQ(sum, static_cast<double>(n * (n - 1) / 2));
}

}  // namespace
}  // namespace toonwater
