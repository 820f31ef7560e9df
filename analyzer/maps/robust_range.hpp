// A robust colour range: the q-quantile (e.g. 98th percentile) of |value| under weights,
// accumulated over any number of samples and frames in constant memory.
//
// The histogram bins are the float values sharing their exponent and top 10 mantissa bits:
// 1024 bins per octave over float's whole range, each at most 1/1024 (0.1 %) of its lower edge
// wide. A quantile is reported as its bin's upper edge: never below the exact weighted
// quantile and at most 0.1 % above it, so that a surface of one curvature (a sphere) shows one
// colour, the colour map's end, within a level.
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

// Colour maps of K and H span [−gaussian, +gaussian] and [−mean, +mean].
struct MapRanges {
  double gaussian = 0;
  double mean = 0;
};

// The one definition of a curvature colour range, shared by the curvature maps
// (map_planner.hpp) and the scene's curvature view (povgen, water.shading): the percentile
// (98th by default) of |K| and of |H| over every vertex added, each weighted by the area it shows
// — the map pixels it covers, or its surface area for a view from a camera — never below the
// curvature of a radius of 10⁴ median edge lengths ℓ (|H| = 10⁻⁴/ℓ, |K| = 10⁻⁸/ℓ²), ℓ the
// smallest over the frames added.
//
// Why weighted: simulation meshes are not uniform (marching cubes refines where the liquid
// curves, and adaptive solvers more so), and an unweighted percentile counts a densely meshed
// detail by its vertices instead of by the picture it covers. Why the floor: flatter than that
// is flat, and a plane's round-off then shows as the zero colour instead of being stretched over
// the whole colour map. Frames accumulate in constant memory, so a sequence of any length pools
// every vertex of every frame.
class CurvatureRanges {
 public:
  void add(double gaussian, double mean, double weight);  // one vertex
  void add_edge_length(double median_edge);  // one frame's; ignored unless positive and finite
  double median_edge() const { return median_edge_; }  // smallest added; 0 when none
  MapRanges ranges(double percentile) const;

 private:
  AbsQuantileHistogram gaussian_, mean_;
  double median_edge_ = 0;
};

}  // namespace toonwater
