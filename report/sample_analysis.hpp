// What the report reads off the curvature study's samples: lookups by surface, sampling, method
// and resolution; observed orders of convergence; error ratios between methods; the best method
// per surface. Every conclusion of the report is computed here from the samples of the run.
#pragma once

#include "report/curvature_study.hpp"

#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace toonwater::report {

// The sample of one method on one surface and sampling at `vertices`, or nullptr.
const StudySample* find(const std::vector<StudySample>& samples, const std::string& surface,
                        const std::string& sampling, const std::string& method,
                        std::size_t vertices);

// The resolutions (vertex counts) sampled on `surface`, ascending.
std::vector<std::size_t> resolutions(const std::vector<StudySample>& samples,
                                     const std::string& surface);

// Observed order of convergence in the mesh spacing h ∝ N^(-1/2), from the coarsest to the
// finest resolution: error ∝ h^p.
double order(const StudySample& coarse, const StudySample& fine, bool mean);

// The smallest and largest of a set of values, as text "lo to hi" ("n/a" when empty).
struct Range {
  double lo = std::numeric_limits<double>::infinity(),
         hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  bool empty() const { return lo > hi; }
  std::string text() const;
};

// Ratios a/b of the RMS errors of two methods over every surface, at resolutions ≥ min_vertices.
Range error_ratio(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& a, const std::string& b, bool mean, std::size_t min_vertices);

// Orders of convergence of one method over every surface.
Range order_range(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& method, bool mean);

// The method with the lowest RMS error in H (then K) at the finest resolution, per surface:
// how many surfaces each method wins.
std::map<std::string, int> winners(const std::vector<StudySample>& samples,
                                   const std::string& sampling);

}  // namespace toonwater::report
