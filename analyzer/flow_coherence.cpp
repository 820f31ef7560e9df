// Temporal coherence of flow regions; the method is stated in flow_coherence.hpp.
#include "analyzer/flow_coherence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace toonwater {

PointGrid::PointGrid(const std::vector<Vec3>& points, double cell_size)
    : points_(points), cell_size_(cell_size > 0.0 ? cell_size : 1.0) {
  std::vector<std::pair<std::int64_t, std::int32_t>> keyed(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    keyed[i] = {key_of(points[i]), static_cast<std::int32_t>(i)};
  std::sort(keyed.begin(), keyed.end());
  order_.resize(keyed.size());
  for (std::size_t i = 0; i < keyed.size(); ++i) {
    order_[i] = keyed[i].second;
    if (cells_.empty() || cells_.back().key != keyed[i].first)
      cells_.push_back({keyed[i].first, static_cast<std::int32_t>(i), static_cast<std::int32_t>(i)});
    cells_.back().end = static_cast<std::int32_t>(i + 1);
  }
}

namespace {

std::int64_t cell_index(double coordinate, double cell_size) {
  constexpr double limit = 1e15;  // far beyond any mesh; keeps the cast defined
  return static_cast<std::int64_t>(std::floor(std::clamp(coordinate / cell_size, -limit, limit)));
}

// Cells are hashed; two cells sharing a key only cost a few extra distance tests.
std::int64_t hash_cell(std::int64_t x, std::int64_t y, std::int64_t z) {
  auto mix = [](std::uint64_t h) {
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdULL;
    h ^= h >> 33;
    return h;
  };
  const std::uint64_t h = mix(static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ULL ^
                              mix(static_cast<std::uint64_t>(y) + 0x632BE59BD9B4E019ULL) ^
                              mix(static_cast<std::uint64_t>(z) * 0x85157AF5ULL));
  return static_cast<std::int64_t>(h >> 1);
}

}  // namespace

std::int64_t PointGrid::key_of(const Vec3& p) const {
  return hash_cell(cell_index(p.x(), cell_size_), cell_index(p.y(), cell_size_),
                   cell_index(p.z(), cell_size_));
}

std::int32_t PointGrid::closest(const Vec3& p) const {
  const std::int64_t cx = cell_index(p.x(), cell_size_), cy = cell_index(p.y(), cell_size_),
                     cz = cell_index(p.z(), cell_size_);
  std::int32_t best = -1;
  double best_distance2 = cell_size_ * cell_size_;
  for (std::int64_t dx = -1; dx <= 1; ++dx)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dz = -1; dz <= 1; ++dz) {
        const std::int64_t key = hash_cell(cx + dx, cy + dy, cz + dz);
        const auto cell = std::lower_bound(cells_.begin(), cells_.end(), key,
                                           [](const Cell& c, std::int64_t k) { return c.key < k; });
        if (cell == cells_.end() || cell->key != key) continue;
        for (std::int32_t i = cell->begin; i < cell->end; ++i) {
          const double d2 = (points_[order_[i]] - p).squaredNorm();
          if (d2 <= best_distance2) {
            best_distance2 = d2;
            best = order_[i];
          }
        }
      }
  return best;
}

FlowFrame flow_frame(const TriangleMesh& surface, const CurvatureField&, const FlowRegions& flow) {
  FlowFrame frame;
  frame.edge_length = flow.median_edge_length;
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    if (flow.free_surface.empty() || !flow.free_surface[v]) continue;
    frame.positions.push_back(surface.positions[v]);
    frame.field.push_back(flow.smoothed_field.empty() ? 0.0 : flow.smoothed_field[v]);
    frame.label.push_back(flow.label[v]);
  }
  return frame;
}

double label_flicker(const FlowFrame& previous, const TriangleMesh& surface,
                     const CurvatureField& curvature, const FlowRegions& flow) {
  const PointGrid grid(previous.positions, CoherenceOptions{}.max_distance * flow.median_edge_length);
  double changed = 0.0, total = 0.0;
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    if (flow.free_surface.empty() || !flow.free_surface[v]) continue;
    const std::int32_t p = grid.closest(surface.positions[v]);
    const std::int8_t before = p >= 0 ? previous.label[p] : std::int8_t{FlowLabel::none};
    total += curvature.area[v];
    if (before != flow.label[v]) changed += curvature.area[v];
  }
  return total > 0.0 ? changed / total : 0.0;
}

void FlowCoherence::apply(const TriangleMesh& surface, const CurvatureField& curvature,
                          FlowRegions& flow) {
  if (!has_previous_) {
    previous_ = flow_frame(surface, curvature, flow);
    has_previous_ = true;
    last_flicker_ = 0.0;
    return;
  }
  const std::size_t n = surface.positions.size();
  const PointGrid grid(previous_.positions, options_.max_distance * flow.median_edge_length);
  const double rise = options_.rise_blend, fall = options_.blend;
  std::vector<double> blended(n, 0.0);
  std::vector<std::int32_t> predecessor(n, -1);
  FlowFrame next;
  next.edge_length = flow.median_edge_length;
  for (std::size_t v = 0; v < n; ++v) {
    if (flow.free_surface.empty() || !flow.free_surface[v]) continue;
    const std::int32_t p = grid.closest(surface.positions[v]);
    predecessor[v] = p;
    const double s = flow.smoothed_field.empty() ? 0.0 : flow.smoothed_field[v];
    if (p >= 0) {
      const double before = previous_.field[p];
      // A field that grows (same sign, larger) is followed faster than one that fades, so a
      // crest that moves a cell or more a frame is not averaged away with the calm water it
      // has left.
      const double b = before * s > 0 && std::abs(s) > std::abs(before) ? rise : fall;
      blended[v] = (1 - b) * s + b * before;
    } else {
      blended[v] = s;
    }
    next.positions.push_back(surface.positions[v]);
    next.field.push_back(blended[v]);
  }
  label_flow_field(surface, curvature.area, std::move(blended), flow);

  double changed = 0.0, total = 0.0;
  for (std::size_t v = 0; v < n; ++v) {
    if (flow.free_surface.empty() || !flow.free_surface[v]) continue;
    const std::int32_t p = predecessor[v];
    const std::int8_t before = p >= 0 ? previous_.label[p] : std::int8_t{FlowLabel::none};
    total += curvature.area[v];
    if (flow.label[v] != before) changed += curvature.area[v];
    next.label.push_back(flow.label[v]);
  }
  last_flicker_ = total > 0.0 ? changed / total : 0.0;
  previous_ = std::move(next);
}

}  // namespace toonwater
