// Closest-point queries within a radius, through a dense uniform grid over the two axes along
// which the points spread most (for a free surface, the horizontal ones): each cell holds the
// points of a column, whatever their height.
//
// Cells are half the radius wide (wider when the points are sparse, so that there are at most
// about four cells a point). A query reads its own cell, then the 2 × 2 cells nearest to it (its
// own and those across its cell's two nearer sides); each holds every point nearer than its
// sides, and when the closest point read is nearer than that, it is the answer. Otherwise the
// query scans the 3 × 3 cells around its own, which hold every point within one cell width, and
// only when none is that close the ring out to 5 × 5, which holds every point within the radius.
// Between two frames of mantaflow-wake 96 % of the free-surface vertices have a predecessor
// within a quarter of an edge (10 % at the same place), so most queries end in their own cell
// (one or two points) and nearly all after the 2 × 2 cells, instead of reading nine or more:
// about 10 ns a query instead of 32 there, single-threaded.
//
// Ties go to the point last in the order of the scans (cell rows in order, each cell's points in
// input order). The cell and the 2 × 2 cells are read in that order and hold every tied point
// when they end the search, so the answer is the one the scans alone would give.
//
// Building is a counting sort on all cores, linear in the points.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace toonwater {

class PointGrid {
 public:
  PointGrid(const std::vector<Vec3>& points, double radius);
  // The same, given the points' bounding box (exactly: the least and greatest coordinates), as
  // a caller that wrote the points may have it without a pass of its own.
  PointGrid(const std::vector<Vec3>& points, double radius, const Box3& bounds);
  // Index (into the points given) of the closest point within `radius` of p, or −1.
  std::int32_t closest(const Vec3& p) const;

 private:
  // The closest point scanned so far: its squared distance and its place in the sorted arrays.
  struct Best {
    double distance2;
    std::int32_t at = -1;
  };
  // Scans the cells (ca + da, cb + db) with max(|da|, |db|) in [inner, outer], row by row.
  void scan(const Vec3& p, std::int64_t ca, std::int64_t cb, int inner, int outer,
            Best& best) const;
  void scan_run(const Vec3& p, std::int32_t begin, std::int32_t end, Best& best) const;
  void sort_into_cells(const std::vector<Vec3>& points);
  // A coordinate along `axis` in cell widths from the origin, and the cell that holds it
  // (−1 or `cells` beyond the grid).
  double cells_from_origin(double coordinate, int axis) const;
  static std::int64_t cell_index(double cells_from_origin, std::int64_t cells);

  double radius_ = 1.0, cell_size_ = 1.0;
  int axis_a_ = 0, axis_b_ = 1;
  Vec3 origin_ = Vec3::Zero();
  std::int64_t cells_a_ = 0, cells_b_ = 0;
  std::vector<std::int32_t> cell_begin_;  // cells_a_ · cells_b_ + 1 offsets into the arrays below
  std::vector<Vec3> sorted_points_;       // the points, cell by cell
  std::vector<std::int32_t> sorted_index_;  // their indices in the input
};

}  // namespace toonwater
