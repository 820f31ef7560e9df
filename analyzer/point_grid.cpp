// Dense column grid; the method is stated in point_grid.hpp.
#include "analyzer/point_grid.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater {

PointGrid::PointGrid(const std::vector<Vec3>& points, double radius)
    : radius_(radius > 0.0 && std::isfinite(radius) ? radius : 1.0) {
  if (points.empty()) return;
  // The bounding box and, below, the points' cells on all cores; the counting sort on one.
  const std::size_t workers = worker_count(points.size());
  std::vector<Vec3> chunk_min(workers, points.front()), chunk_max(workers, points.front());
  parallel_chunks(points.size(), workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      chunk_min[chunk] = chunk_min[chunk].cwiseMin(points[i]);
      chunk_max[chunk] = chunk_max[chunk].cwiseMax(points[i]);
    }
  });
  Vec3 min = chunk_min[0], max = chunk_max[0];
  for (std::size_t w = 1; w < workers; ++w) {
    min = min.cwiseMin(chunk_min[w]);
    max = max.cwiseMax(chunk_max[w]);
  }
  const Vec3 extent = max - min;
  int thinnest = 0;
  for (int axis = 1; axis < 3; ++axis)
    if (extent[axis] < extent[thinnest]) thinnest = axis;
  axis_a_ = thinnest == 0 ? 1 : 0;
  axis_b_ = thinnest == 2 ? 1 : 2;
  origin_ = min;
  // At most about four cells a point: sparse points (a droplet flung far) get wider cells.
  const double n = static_cast<double>(points.size());
  cell_size_ = std::max(0.5 * radius_, std::sqrt(extent[axis_a_] * extent[axis_b_] / (4.0 * n)));
  cell_size_ = std::max({cell_size_, extent[axis_a_] / 1e6, extent[axis_b_] / 1e6});
  cells_a_ = static_cast<std::int64_t>(extent[axis_a_] / cell_size_) + 1;
  cells_b_ = static_cast<std::int64_t>(extent[axis_b_] / cell_size_) + 1;

  std::vector<std::int64_t> cell_of(points.size());
  parallel_chunks(points.size(), workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      cell_of[i] = cell_along(points[i][axis_a_], axis_a_) * cells_b_ +
                   cell_along(points[i][axis_b_], axis_b_);
  });
  cell_begin_.assign(static_cast<std::size_t>(cells_a_ * cells_b_ + 1), 0);
  for (std::size_t i = 0; i < points.size(); ++i) ++cell_begin_[cell_of[i] + 1];
  for (std::size_t c = 1; c < cell_begin_.size(); ++c) cell_begin_[c] += cell_begin_[c - 1];
  std::vector<std::int32_t> fill(cell_begin_.begin(), cell_begin_.end() - 1);
  sorted_points_.resize(points.size());
  sorted_index_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::int32_t at = fill[cell_of[i]]++;
    sorted_points_[at] = points[i];
    sorted_index_[at] = static_cast<std::int32_t>(i);
  }
}

std::int64_t PointGrid::cell_along(double coordinate, int axis) const {
  const std::int64_t cells = axis == axis_a_ ? cells_a_ : cells_b_;
  const double t = std::floor((coordinate - origin_[axis]) / cell_size_);
  return static_cast<std::int64_t>(std::clamp(t, -1.0, static_cast<double>(cells)));
}

// The closest point so far, with its place in the order of a full scan (which breaks ties).
struct PointGrid::Best {
  double distance2;
  std::int32_t order = -1;  // position in the sorted arrays, plus an offset for the ring
  std::int32_t index = -1;
};

void PointGrid::search_cell(const Vec3& p, std::int64_t a, std::int64_t b,
                            std::int32_t order_offset, Best& best) const {
  const std::int64_t cell = a * cells_b_ + b;
  const std::int32_t end = cell_begin_[cell + 1];
  for (std::int32_t i = cell_begin_[cell]; i < end; ++i) {
    const double d2 = (sorted_points_[i] - p).squaredNorm();
    if (d2 < best.distance2 || (d2 == best.distance2 && i + order_offset > best.order))
      best = Best{d2, i + order_offset, sorted_index_[i]};
  }
}

void PointGrid::search(const Vec3& p, std::int64_t ca, std::int64_t cb, int inner, int outer,
                       std::int32_t order_offset, Best& best) const {
  // The query's distance, in cell widths, to a row or column `d` cells away: a cell is skipped
  // when it is farther than the best point found, so that no point in it can be closer or tie.
  // A millionth of a cell off the gap keeps the bound below the distance of every point the
  // build sorted into the cell, whatever the round-off of its floor((x − origin) / cell).
  const double ta = (p[axis_a_] - origin_[axis_a_]) / cell_size_,
               tb = (p[axis_b_] - origin_[axis_b_]) / cell_size_;
  auto gap2 = [&](double t, std::int64_t cell) {
    const double cell_double = static_cast<double>(cell);
    const double gap = std::max({cell_double - t, t - (cell_double + 1.0), 0.0}) - 1e-6;
    return gap > 0.0 ? gap * gap * cell_size_ * cell_size_ : 0.0;
  };
  for (std::int64_t da = -outer; da <= outer; ++da) {
    const std::int64_t a = ca + da;
    if (a < 0 || a >= cells_a_) continue;
    const double row_gap2 = gap2(ta, a);
    if (row_gap2 > best.distance2) continue;
    for (std::int64_t db = -outer; db <= outer; ++db) {
      const std::int64_t b = cb + db;
      if (b < 0 || b >= cells_b_ || std::max(std::abs(da), std::abs(db)) < inner) continue;
      if (da == 0 && db == 0) continue;  // searched first, by closest()
      if (row_gap2 + gap2(tb, b) > best.distance2) continue;
      search_cell(p, a, b, order_offset, best);
    }
  }
}

std::int32_t PointGrid::closest(const Vec3& p) const {
  if (sorted_points_.empty()) return -1;
  Best best{radius_ * radius_};
  const std::int64_t ca = cell_along(p[axis_a_], axis_a_), cb = cell_along(p[axis_b_], axis_b_);
  if (ca >= 0 && ca < cells_a_ && cb >= 0 && cb < cells_b_) search_cell(p, ca, cb, 0, best);
  search(p, ca, cb, 0, 1, 0, best);
  if (best.index >= 0 && best.distance2 <= cell_size_ * cell_size_) return best.index;
  // The ring out to two cells holds every point within 2 cell widths >= the radius; in a full
  // scan it comes after the block.
  search(p, ca, cb, 2, 2, static_cast<std::int32_t>(sorted_points_.size()), best);
  return best.index;
}

}  // namespace toonwater
