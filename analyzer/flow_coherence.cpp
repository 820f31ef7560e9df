// Temporal coherence of flow regions; the method is stated in flow_coherence.hpp.
#include "analyzer/flow_coherence.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

namespace toonwater {

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
  const PointGrid grid(previous.positions,
                       CoherenceOptions{}.max_distance * flow.median_edge_length);
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

void FlowCoherence::blend(const TriangleMesh& surface, const FlowRegions& flow,
                          std::vector<double>& field, std::vector<Vec3>& shading_normal) {
  const std::size_t n = surface.positions.size();
  const bool any_surface = flow.free_surface.size() == n;
  const std::optional<PointGrid> grid =
      has_previous_ ? std::optional<PointGrid>(std::in_place, previous_.positions,
                                               options_.max_distance * flow.median_edge_length,
                                               previous_bounds_)
                    : std::nullopt;
  // The free-surface vertices are numbered compactly in vertex order: counted chunk by chunk
  // (a byte a vertex, quicker on one core than waking another), then each chunk fills its part
  // of the pending frame from its own offset.
  const std::size_t workers = chunk_count(n, 4096);
  std::vector<std::size_t> chunk_begin(workers + 1, 0);
  for (std::size_t chunk = 0; chunk < workers && any_surface; ++chunk) {
    std::size_t count = 0;
    for (std::size_t v = n * chunk / workers; v < n * (chunk + 1) / workers; ++v)
      count += flow.free_surface[v];
    chunk_begin[chunk + 1] = chunk_begin[chunk] + count;
  }
  // The buffers of the frame before last are reused: no new pages each frame.
  pending_.edge_length = flow.median_edge_length;
  pending_.positions.resize(chunk_begin.back());
  pending_.field.resize(chunk_begin.back());
  const bool normals = shading_normal.size() == n;
  pending_.shading_normal.resize(normals ? chunk_begin.back() : 0);
  const bool normals_before =
      normals && previous_.shading_normal.size() == previous_.positions.size();
  pending_.label.resize(chunk_begin.back());
  predecessor_.resize(n);
  // The pending frame's bounding box, chunk by chunk, from the positions as they are copied:
  // the next frame's grid needs it, and a pass of its own would read them all again.
  std::vector<Box3> chunk_bounds(workers, Box3::of_no_points());
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    if (!any_surface) {
      std::fill(predecessor_.begin() + static_cast<std::ptrdiff_t>(begin),
                predecessor_.begin() + static_cast<std::ptrdiff_t>(end), -1);
      return;
    }
    // By plain pointers and values: the search is a call, after which the compiler would load
    // every member array's address again.
    const std::uint8_t* const on_surface = flow.free_surface.data();
    const Vec3* const position = surface.positions.data();
    const double* const field_before = previous_.field.data();
    double* const s = field.data();
    std::int32_t* const predecessor = predecessor_.data();
    Vec3* const next_position = pending_.positions.data();
    double* const next_field = pending_.field.data();
    const PointGrid* const previous_surface = grid ? &*grid : nullptr;
    const double blend = options_.blend, rise_blend = options_.rise_blend;
    const double normal_blend = options_.normal_blend;
    const double normal_change_limit = options_.normal_noise_multiple * flow.normal_noise;
    std::size_t next = chunk_begin[chunk];
    Box3 bounds =
        Box3::of_no_points();  // in a local: in the vector, each update would wait for a store
    for (std::size_t v = begin; v < end; ++v) {
      predecessor[v] = -1;
      if (!on_surface[v]) continue;
      const std::int32_t p = previous_surface ? previous_surface->closest(position[v]) : -1;
      predecessor[v] = p;
      if (p >= 0) {
        const double now = s[v], before = field_before[p];
        // A field that grows (same sign, larger) is followed faster than one that fades, so a
        // crest that moves a cell or more a frame is not averaged away with the calm water it
        // has left.
        const double b = before * now > 0 && std::abs(now) > std::abs(before) ? rise_blend : blend;
        s[v] = (1 - b) * now + b * before;
        // Undefined normals (zero) are neither blended nor blended into.
        if (normals_before && normal_change_limit > 0.0 && shading_normal[v].squaredNorm() > 0.5 &&
            previous_.shading_normal[p].squaredNorm() > 0.5) {
          const Vec3& normal_before = previous_.shading_normal[p];
          const double change = (shading_normal[v] - normal_before).norm() / normal_change_limit;
          const double normal_weight = normal_blend * std::max(0.0, 1.0 - change * change);
          const Vec3 mixed =
              (1 - normal_weight) * shading_normal[v] + normal_weight * normal_before;
          if (mixed.squaredNorm() > 0.0) shading_normal[v] = mixed.normalized();
        }
      }
      next_position[next] = position[v];
      next_field[next] = s[v];
      if (normals) pending_.shading_normal[next] = shading_normal[v];
      ++next;
      bounds.add(position[v]);
    }
    chunk_bounds[chunk] = bounds;
  });
  pending_bounds_ = Box3::of_no_points();
  for (const Box3& bounds : chunk_bounds) pending_bounds_.add(bounds);
}

void FlowCoherence::remember(const CurvatureField& curvature, const FlowRegions& flow) {
  // On one core, the areas summed in vertex order, so that the flicker does not depend on the
  // number of cores.
  double changed = 0.0, total = 0.0;
  if (flow.free_surface.size() == predecessor_.size()) {
    // By plain pointers: after the labels' byte stores the compiler would load every vector's
    // address again.
    const std::uint8_t* const on_surface = flow.free_surface.data();
    const std::int8_t *const label = flow.label.data(), *const label_before =
                                                            previous_.label.data();
    const std::int32_t* const predecessor = predecessor_.data();
    const double* const area = curvature.area.data();
    std::int8_t* const next_label = pending_.label.data();
    std::size_t next = 0;
    for (std::size_t v = 0; v < predecessor_.size(); ++v) {
      if (!on_surface[v]) continue;
      const std::int32_t p = predecessor[v];
      const std::int8_t before = p >= 0 ? label_before[p] : std::int8_t{FlowLabel::none};
      total += area[v];
      if (label[v] != before) changed += area[v];
      next_label[next++] = label[v];
    }
  }
  last_flicker_ = has_previous_ && total > 0.0 ? changed / total : 0.0;
  std::swap(previous_, pending_);
  std::swap(previous_bounds_, pending_bounds_);
  has_previous_ = true;
}

double FlowCoherence::sequence_noise_floor(double frame_noise_floor) {
  if (frame_noise_floor > 0.0 && std::isfinite(frame_noise_floor))
    noise_floors_.push_back(frame_noise_floor);
  if (noise_floors_.empty()) return 0.0;
  std::vector<double> sorted = noise_floors_;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  return m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
}

void FlowCoherence::apply(const TriangleMesh& surface, const CurvatureField& curvature,
                          FlowRegions& flow) {
  std::vector<double> field = flow.smoothed_field;
  field.resize(surface.positions.size(), 0.0);
  const bool first = !has_previous_;
  blend(surface, flow, field, flow.shading_normal);
  if (!first) label_flow_field(surface, curvature.area, std::move(field), flow);
  remember(curvature, flow);
}

}  // namespace toonwater
