// The k-th smallest double, selected among a few; the method is stated in order_statistic.hpp.
#include "common/order_statistic.hpp"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace toonwater {
namespace {

// nth_element on these many or fewer values directly: the sample would cost more than it saves.
constexpr std::size_t few_values = 4096;
constexpr std::size_t sample_size = 1024;
constexpr std::size_t bound_margin = sample_size * 4 / 100;  // sample ranks either side of k's

double nth_element_at(double* first, double* last, std::size_t k) {
  const auto kth = first + static_cast<std::ptrdiff_t>(k);
  std::nth_element(first, kth, last);
  return *kth;
}

}  // namespace

double kth_smallest(std::span<double> values, std::size_t k) {
  const std::size_t n = values.size();
  if (n <= few_values) return nth_element_at(values.data(), values.data() + n, k);
  std::vector<double> sample(sample_size);
  for (std::size_t i = 0; i < sample_size; ++i)
    sample[i] = values[static_cast<std::size_t>((std::uint64_t{i} * 2654435761u) % n)];
  const std::size_t at = k * sample_size / n;
  const std::size_t low_rank = at > bound_margin ? at - bound_margin : 0;
  const std::size_t high_rank = std::min(at + bound_margin, sample_size - 1);
  double* const sampled = sample.data();
  const double low = nth_element_at(sampled, sampled + sample_size, low_rank);
  const double high = nth_element_at(sampled + low_rank, sampled + sample_size, high_rank - low_rank);
  // The values between the bounds moved to the front, without a branch on the bounds: every
  // value is swapped with the next place, which advances only past those between them. (A new
  // array for them cost more than the pass, in page faults.)
  double* const value = values.data();
  std::size_t below = 0, kept = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double v = value[i];
    below += v < low;
    value[i] = value[kept];
    value[kept] = v;
    kept += (v >= low) & (v <= high);
  }
  if (below <= k && k < below + kept) return nth_element_at(value, value + kept, k - below);
  return nth_element_at(value, value + n, k);
}

}  // namespace toonwater
