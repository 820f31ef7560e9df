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

void PointGrid::scan(const Vec3& p, std::int64_t ca, std::int64_t cb, int inner, int outer,
                     std::int32_t& best, double& best_distance2) const {
  // The cells of a row are consecutive in the sorted arrays, so a run of them is one range.
  auto scan_run = [&](std::int64_t a, std::int64_t b_first, std::int64_t b_last) {
    b_first = std::max<std::int64_t>(b_first, 0);
    b_last = std::min<std::int64_t>(b_last, cells_b_ - 1);
    if (b_first > b_last) return;
    const std::int32_t end = cell_begin_[a * cells_b_ + b_last + 1];
    for (std::int32_t i = cell_begin_[a * cells_b_ + b_first]; i < end; ++i) {
      const double d2 = (sorted_points_[i] - p).squaredNorm();
      if (d2 <= best_distance2) {
        best_distance2 = d2;
        best = sorted_index_[i];
      }
    }
  };
  for (std::int64_t da = -outer; da <= outer; ++da) {
    const std::int64_t a = ca + da;
    if (a < 0 || a >= cells_a_) continue;
    if (std::abs(da) >= inner) {
      scan_run(a, cb - outer, cb + outer);
    } else {  // the row crosses the hole of the ring: its two ends
      scan_run(a, cb - outer, cb - inner);
      scan_run(a, cb + inner, cb + outer);
    }
  }
}

std::int32_t PointGrid::closest(const Vec3& p) const {
  std::int32_t best = -1;
  if (sorted_points_.empty()) return best;
  double best_distance2 = radius_ * radius_;
  const std::int64_t ca = cell_along(p[axis_a_], axis_a_), cb = cell_along(p[axis_b_], axis_b_);
  scan(p, ca, cb, 0, 1, best, best_distance2);
  if (best >= 0 && best_distance2 <= cell_size_ * cell_size_) return best;
  // The ring out to two cells holds every point within 2 cell widths >= the radius.
  scan(p, ca, cb, 2, 2, best, best_distance2);
  return best;
}

}  // namespace toonwater
