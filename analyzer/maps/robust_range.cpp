// Weighted quantile of |value| from a log-binned histogram (see robust_range.hpp). A positive
// float's bit pattern grows with its value, so the pattern shifted right by 13 bits (dropping
// all but the exponent and the top 10 mantissa bits) is a monotone bin index: 2^18 bins (2 MB),
// 1024 per octave, no logarithm needed.
#include "analyzer/maps/robust_range.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

namespace toonwater {
namespace {

constexpr int dropped_bits = 13;
constexpr std::size_t bin_count = std::size_t{1} << (31 - dropped_bits);

std::size_t bin_of(double magnitude) {
  constexpr double largest = std::numeric_limits<float>::max();
  const float f = static_cast<float>(std::min(magnitude, largest));
  return std::bit_cast<std::uint32_t>(f) >> dropped_bits;
}

double upper_edge(std::size_t bin) {
  const auto bits = static_cast<std::uint32_t>((bin + 1) << dropped_bits);
  const float edge = std::bit_cast<float>(bits);
  return std::isfinite(edge) ? edge : std::numeric_limits<float>::max();
}

}  // namespace

AbsQuantileHistogram::AbsQuantileHistogram() : weight_(bin_count, 0.0) {}

void AbsQuantileHistogram::add(double value, double weight) {
  if (std::isnan(value) || !(weight > 0.0) || !std::isfinite(weight)) return;
  weight_[bin_of(std::abs(value))] += weight;
  total_ += weight;
}

void AbsQuantileHistogram::merge(const AbsQuantileHistogram& other) {
  for (std::size_t b = 0; b < bin_count; ++b) weight_[b] += other.weight_[b];
  total_ += other.total_;
}

double AbsQuantileHistogram::quantile(double q) const {
  if (!(total_ > 0.0)) return 0.0;
  const double target = std::clamp(q, 0.0, 1.0) * total_;
  double cumulative = 0.0;
  for (std::size_t b = 0; b < bin_count; ++b) {
    cumulative += weight_[b];
    // Zeros (bin 0 holds 0 and the tiniest subnormals) report 0, not a subnormal edge.
    if (cumulative >= target && weight_[b] > 0.0) return b == 0 ? 0.0 : upper_edge(b);
  }
  return upper_edge(bin_count - 1);
}

void CurvatureRanges::add(double gaussian, double mean, double weight) {
  gaussian_.add(gaussian, weight);
  mean_.add(mean, weight);
}

void CurvatureRanges::add_edge_length(double median_edge) {
  if (median_edge > 0.0 && std::isfinite(median_edge))
    median_edge_ = median_edge_ > 0.0 ? std::min(median_edge_, median_edge) : median_edge;
}

MapRanges CurvatureRanges::ranges(double percentile) const {
  constexpr double flat_radius_in_edges = 1e4;
  const double min_mean = median_edge_ > 0.0 ? 1.0 / (flat_radius_in_edges * median_edge_) : 0.0;
  return {std::max(gaussian_.quantile(percentile), min_mean * min_mean),
          std::max(mean_.quantile(percentile), min_mean)};
}

}  // namespace toonwater
