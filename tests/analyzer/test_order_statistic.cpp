// kth_smallest: the value std::nth_element finds, for every rank asked, on values that are
// random, sorted, periodic (as a mesh's edges are), heavily repeated, signed, and spread over
// many orders of magnitude.
#include "common/order_statistic.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace toonwater {
namespace {

double nth_element_value(std::vector<double> values, std::size_t k) {
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

void expect_as_nth_element(const std::vector<double>& values, const char* what) {
  const std::size_t n = values.size();
  for (const std::size_t k : {std::size_t{0}, n / 100, n / 3, n / 2, n - 1 - n / 100, n - 1}) {
    std::vector<double> copy = values;
    EXPECT_EQ(kth_smallest(copy, k), nth_element_value(values, k)) << what << ", n = " << n << ", k = " << k;
  }
}

TEST(KthSmallest, IsTheValueNthElementFinds) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> unit(0.0, 1.0), exponent(-30.0, 30.0);
  for (const std::size_t n : {1u, 2u, 100u, 4096u, 4097u, 50000u, 200000u}) {
    std::vector<double> random(n), sorted(n), periodic(n), repeated(n), signed_values(n), spread(n);
    for (std::size_t i = 0; i < n; ++i) {
      random[i] = unit(rng);
      sorted[i] = static_cast<double>(i);
      periodic[i] = std::sin(0.0123 * static_cast<double>(i % 235)) + 1e-3 * static_cast<double>(i % 7);
      repeated[i] = static_cast<double>(rng() % 3);
      signed_values[i] = rng() % 4 == 0 ? 0.0 : unit(rng) - 0.5;
      spread[i] = std::pow(10.0, exponent(rng));
    }
    expect_as_nth_element(random, "random");
    expect_as_nth_element(sorted, "sorted");
    expect_as_nth_element(periodic, "periodic");
    expect_as_nth_element(repeated, "three values");
    expect_as_nth_element(signed_values, "signed, with zeros");
    expect_as_nth_element(spread, "60 orders of magnitude");
  }
}

}  // namespace
}  // namespace toonwater
