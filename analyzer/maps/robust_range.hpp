// A robust colour range: the q-quantile (e.g. 98th percentile) of |value| under weights,
// accumulated over any number of samples and frames in constant memory.
//
// The histogram bins are the float values sharing their exponent and top 6 mantissa bits:
// 64 bins per octave over float's whole range, each at most 1/64 (1.6 %) of its lower edge
// wide. A quantile is reported as its bin's upper edge: never below the exact weighted
// quantile and at most 1.6 % above it.
#pragma once

#include <cstdint>
#include <vector>

namespace toonwater {

class AbsQuantileHistogram {
 public:
  AbsQuantileHistogram();
  void add(double value, double weight);  // ignores NaN and non-positive weights
  void merge(const AbsQuantileHistogram& other);
  double total_weight() const { return total_; }
  // Smallest bin edge x with weight(|value| ≤ x) ≥ q · total; 0 when empty.
  double quantile(double q) const;

 private:
  std::vector<double> weight_;  // per bin
  double total_ = 0;
};

}  // namespace toonwater
