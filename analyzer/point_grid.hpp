// Closest-point queries within a radius, through a dense uniform grid over the two axes along
// which the points spread most (for a free surface, the horizontal ones): each cell holds the
// points of a column, whatever their height.
//
// Cells are half the radius wide (wider when the points are sparse, so that there are at most
// about four cells a point). A query first scans the 3 × 3 cells around its own, which hold
// every point within one cell width; only when none is that close does it scan the ring out to
// 5 × 5, which holds every point within the radius. Between two frames of a simulation nearly
// every vertex has a predecessor within half an edge or so, so nearly every query ends after
// the first block, reading a few neighbouring rows of one array. Building is a counting sort:
// linear in the points.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstdint>
#include <vector>

namespace toonwater {

class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, double radius);
  // Index (into the points given) of the closest point within `radius` of p, or −1.
  std::int32_t closest(const Vec3& p) const;

 private:
  // Scans the cells (ca + da, cb + db) with max(|da|, |db|) in [inner, outer].
  void scan(const Vec3& p, std::int64_t ca, std::int64_t cb, int inner, int outer,
            std::int32_t& best, double& best_distance2) const;
  std::int64_t cell_along(double coordinate, int axis) const;

  double radius_ = 1.0, cell_size_ = 1.0;
  int axis_a_ = 0, axis_b_ = 1;
  Vec3 origin_ = Vec3::Zero();
  std::int64_t cells_a_ = 0, cells_b_ = 0;
  std::vector<std::int32_t> cell_begin_;  // cells_a_ · cells_b_ + 1 offsets into the arrays below
  std::vector<Vec3> sorted_points_;       // the points, cell by cell
  std::vector<std::int32_t> sorted_index_;  // their indices in the input
};

}  // namespace toonwater
