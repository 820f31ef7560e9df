// Dense column grid; the method is stated in point_grid.hpp.
#include "analyzer/point_grid.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>

namespace toonwater {

namespace {

// The points' bounding box, on all cores.
Box3 bounding_box(const std::vector<Vec3>& points) {
  if (points.empty()) return Box3{};
  const std::size_t workers = chunk_count(points.size());
  std::vector<Box3> chunk_box(workers);
  parallel_chunks(points.size(), workers,
                  [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                    // In a local: kept in the vector, each point's update waited for the last one's
                    // store.
                    Box3 box = Box3::of_no_points();
                    for (std::size_t i = begin; i < end; ++i) box.add(points[i]);
                    chunk_box[chunk] = box;
                  });
  Box3 box = Box3::of_no_points();
  for (const Box3& chunk : chunk_box) box.add(chunk);
  return box;
}

}  // namespace

PointGrid::PointGrid(const std::vector<Vec3>& points, double radius)
    : PointGrid(points, radius, bounding_box(points)) {}

PointGrid::PointGrid(const std::vector<Vec3>& points, double radius, const Box3& bounds)
    : radius_(radius > 0.0 && std::isfinite(radius) ? radius : 1.0) {
  if (points.empty()) return;
  const Vec3 &min = bounds.min, &max = bounds.max;
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

  sort_into_cells(points);
}

// A counting sort on all cores that keeps each cell's points in input order: every chunk of
// points counts its points per cell in an array of its own, the offsets are taken cell by
// cell and within a cell chunk by chunk, and every chunk then places its points.
void PointGrid::sort_into_cells(const std::vector<Vec3>& points) {
  const std::size_t n = points.size(), cell_count = static_cast<std::size_t>(cells_a_ * cells_b_);
  const std::size_t workers = chunk_count(n);
  // Left uninitialised by new: each chunk writes its points' cells and zeroes its own counts.
  std::unique_ptr<std::int32_t[]> cell_of(new std::int32_t[n]);
  std::unique_ptr<std::int32_t[]> counts(new std::int32_t[workers * cell_count]);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::int32_t* const count = counts.get() + chunk * cell_count;
    std::fill(count, count + cell_count, 0);
    // The points lie inside the grid, where truncation is cell_index's floor.
    for (std::size_t i = begin; i < end; ++i) {
      cell_of[i] = static_cast<std::int32_t>(
          static_cast<std::int64_t>(cells_from_origin(points[i][axis_a_], axis_a_)) * cells_b_ +
          static_cast<std::int64_t>(cells_from_origin(points[i][axis_b_], axis_b_)));
      ++count[cell_of[i]];
    }
  });
  // The offsets over ranges of cells: each range's total, then each range from the totals of
  // those before it. A chunk's count becomes the place of its first point in the cell.
  const std::size_t cell_workers = chunk_count(cell_count);
  std::vector<std::int32_t> range_begin(cell_workers + 1, 0);
  parallel_chunks(cell_count, cell_workers,
                  [&](std::size_t range, std::size_t begin, std::size_t end) {
                    std::int32_t total = 0;
                    for (std::size_t chunk = 0; chunk < workers; ++chunk)
                      for (std::size_t cell = begin; cell < end; ++cell)
                        total += counts[chunk * cell_count + cell];
                    range_begin[range + 1] = total;
                  });
  std::partial_sum(range_begin.begin(), range_begin.end(), range_begin.begin());
  cell_begin_.resize(cell_count + 1);
  parallel_chunks(cell_count, cell_workers,
                  [&](std::size_t range, std::size_t begin, std::size_t end) {
                    std::int32_t next = range_begin[range];
                    for (std::size_t cell = begin; cell < end; ++cell) {
                      cell_begin_[cell] = next;
                      for (std::size_t chunk = 0; chunk < workers; ++chunk) {
                        std::int32_t& count = counts[chunk * cell_count + cell];
                        const std::int32_t points_here = count;
                        count = next;
                        next += points_here;
                      }
                    }
                  });
  cell_begin_[cell_count] = static_cast<std::int32_t>(n);
  sorted_points_.resize(n);
  sorted_index_.resize(n);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::int32_t* const place = counts.get() + chunk * cell_count;
    for (std::size_t i = begin; i < end; ++i) {
      const std::int32_t at = place[cell_of[i]]++;
      sorted_points_[at] = points[i];
      sorted_index_[at] = static_cast<std::int32_t>(i);
    }
  });
}

double PointGrid::cells_from_origin(double coordinate, int axis) const {
  return (coordinate - origin_[axis]) / cell_size_;
}

std::int64_t PointGrid::cell_index(double cells_from_origin, std::int64_t cells) {
  return static_cast<std::int64_t>(
      std::clamp(std::floor(cells_from_origin), -1.0, static_cast<double>(cells)));
}

// Every point of the run against the best so far, without a branch on the comparison: about
// one point in three is closer than those before it, an outcome no predictor learns. Ties go
// to the later point.
void PointGrid::scan_run(const Vec3& p, std::int32_t begin, std::int32_t end, Best& best) const {
  for (std::int32_t i = begin; i < end; ++i) {
    const double d2 = (sorted_points_[i] - p).squaredNorm();
    // A mask, not a conditional: the compiler turns `closer ? i : at` back into a branch.
    const std::int32_t closer = -static_cast<std::int32_t>(d2 <= best.distance2);
    best.at = (i & closer) | (best.at & ~closer);
    best.distance2 = std::min(best.distance2, d2);
  }
}

void PointGrid::scan(const Vec3& p, std::int64_t ca, std::int64_t cb, int inner, int outer,
                     Best& best) const {
  // The cells of a row are consecutive in the sorted arrays, so a run of them is one range.
  auto run = [&](std::int64_t a, std::int64_t b_first, std::int64_t b_last) {
    b_first = std::max<std::int64_t>(b_first, 0);
    b_last = std::min<std::int64_t>(b_last, cells_b_ - 1);
    if (b_first > b_last) return;
    scan_run(p, cell_begin_[a * cells_b_ + b_first], cell_begin_[a * cells_b_ + b_last + 1], best);
  };
  for (std::int64_t da = -outer; da <= outer; ++da) {
    const std::int64_t a = ca + da;
    if (a < 0 || a >= cells_a_) continue;
    if (std::abs(da) >= inner) {
      run(a, cb - outer, cb + outer);
    } else {  // the row crosses the hole of the ring: its two ends
      run(a, cb - outer, cb - inner);
      run(a, cb + inner, cb + outer);
    }
  }
}

std::int32_t PointGrid::closest(const Vec3& p) const {
  if (sorted_points_.empty()) return -1;
  const double ta = cells_from_origin(p[axis_a_], axis_a_),
               tb = cells_from_origin(p[axis_b_], axis_b_);
  Best best{radius_ * radius_};
  if (ta >= 0.0 && ta < static_cast<double>(cells_a_) && tb >= 0.0 &&
      tb < static_cast<double>(cells_b_)) {
    // Inside the grid, where truncation is cell_index's floor. First the query's own cell, then
    // the 2 × 2 cells nearest it (its own and those across its cell's nearer sides). Each holds
    // every point nearer than its `reach`, the query's distance to its sides (for the block at
    // least half a cell), less a millionth of a cell for the round-off of the cells'
    // floor((x − o) / w). A point found nearer than that is nearer than any outside, so the
    // full scans below would end at it too: ties within the block go to the later point in both.
    const auto ca = static_cast<std::int64_t>(ta), cb = static_cast<std::int64_t>(tb);
    const double fa = ta - static_cast<double>(ca), fb = tb - static_cast<double>(cb);
    auto closer_than = [&](double reach) {
      reach = (reach - 1e-6) * cell_size_;
      return best.at >= 0 && best.distance2 < reach * reach;
    };
    scan_run(p, cell_begin_[ca * cells_b_ + cb], cell_begin_[ca * cells_b_ + cb + 1], best);
    if (closer_than(std::min({fa, 1.0 - fa, fb, 1.0 - fb}))) return sorted_index_[best.at];
    best = Best{radius_ * radius_};
    const std::int64_t a = fa < 0.5 ? ca - 1 : ca, b = fb < 0.5 ? cb - 1 : cb;
    for (std::int64_t row = std::max<std::int64_t>(a, 0); row <= std::min(a + 1, cells_a_ - 1);
         ++row)
      scan_run(p, cell_begin_[row * cells_b_ + std::max<std::int64_t>(b, 0)],
               cell_begin_[row * cells_b_ + std::min(b + 1, cells_b_ - 1) + 1], best);
    if (closer_than(std::min(std::max(fa, 1.0 - fa), std::max(fb, 1.0 - fb))))
      return sorted_index_[best.at];
    best = Best{radius_ * radius_};
  }
  const std::int64_t ca = cell_index(ta, cells_a_), cb = cell_index(tb, cells_b_);
  scan(p, ca, cb, 0, 1, best);
  // The ring out to two cells holds every point within 2 cell widths >= the radius.
  if (best.at < 0 || best.distance2 > cell_size_ * cell_size_) scan(p, ca, cb, 2, 2, best);
  return best.at < 0 ? -1 : sorted_index_[best.at];
}

}  // namespace toonwater
