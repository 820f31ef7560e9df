// Temporal coherence of flow regions; the method is stated in flow_coherence.hpp.
#include "analyzer/flow_coherence.hpp"

#include "analyzer/closest_point.hpp"
#include "analyzer/disjoint_sets.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <utility>

namespace toonwater {
namespace {

// The connected parts of one sign: vertices of the same non-zero sign joined along the edges
// between them, numbered in vertex order; their areas summed in vertex order, so that they do
// not depend on the core count.
struct SignedParts {
  std::vector<std::int32_t> part;  // per vertex; −1 where the sign is 0
  std::vector<double> area;
};

SignedParts signed_parts(const TriangleMesh& mesh, std::span<const std::int8_t> sign,
                         std::span<const double> vertex_area) {
  const std::size_t n = sign.size();
  DisjointSets sets(n);
  for (const Triangle& t : mesh.triangles)
    for (int corner = 0; corner < 3; ++corner) {
      const std::int32_t a = t[corner], b = t[(corner + 1) % 3];
      if (sign[a] != FlowLabel::none && sign[a] == sign[b]) sets.join(a, b);
    }
  SignedParts parts;
  parts.part.assign(n, -1);
  std::vector<std::int32_t> part_of_root(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (sign[v] == FlowLabel::none) continue;
    std::int32_t& part = part_of_root[sets.root(static_cast<std::int32_t>(v))];
    if (part < 0) {
      part = static_cast<std::int32_t>(parts.area.size());
      parts.area.push_back(0.0);
    }
    parts.part[v] = part;
    parts.area[part] += vertex_area[v];
  }
  return parts;
}

// Where the previous frame's values are carried from for a vertex at x whose predecessor is p:
// the point of p's faces closest to x, as its corners and their weights; p alone where it has
// no face.
struct CarriedPoint {
  Triangle corner;
  Vec3 weight;
};

CarriedPoint closest_on_faces_around(const FlowFrame& frame, std::int32_t p, const Vec3& x) {
  CarriedPoint carried{{p, p, p}, Vec3(1, 0, 0)};
  double closest2 = std::numeric_limits<double>::infinity();
  for (const std::int32_t f : frame.vertex_faces.of(p)) {
    const Triangle& t = frame.triangles[static_cast<std::size_t>(f)];
    const TrianglePoint q = closest_point_on_triangle(x, frame.positions[t[0]],
                                                      frame.positions[t[1]], frame.positions[t[2]]);
    if (q.distance2 < closest2) {
      closest2 = q.distance2;
      carried = {t, q.weights};
    }
  }
  return carried;
}

// A per-vertex value (the field, a normal) of the previous frame at the carried point.
template <class Value>
Value carried_value(const Value* values, const CarriedPoint& from) {
  return from.weight[0] * values[from.corner[0]] + from.weight[1] * values[from.corner[1]] +
         from.weight[2] * values[from.corner[2]];
}

// The free surface's faces in its own numbering (`surface_index`, −1 off it): those with every
// corner on it.
std::vector<Triangle> free_surface_faces(const TriangleMesh& mesh,
                                         std::span<const std::int32_t> surface_index) {
  std::vector<Triangle> faces;
  for (const Triangle& t : mesh.triangles) {
    if (has_repeated_corner(t)) continue;
    const Triangle face{surface_index[t[0]], surface_index[t[1]], surface_index[t[2]]};
    if (face[0] >= 0 && face[1] >= 0 && face[2] >= 0) faces.push_back(face);
  }
  return faces;
}

}  // namespace

FlowFrame flow_frame(const TriangleMesh& surface, const CurvatureField&, const FlowRegions& flow) {
  FlowFrame frame;
  frame.edge_length = flow.median_edge_length;
  std::vector<std::int32_t> surface_index(surface.positions.size(), -1);
  for (std::size_t v = 0; v < surface.positions.size(); ++v) {
    if (flow.free_surface.empty() || !flow.free_surface[v]) continue;
    surface_index[v] = static_cast<std::int32_t>(frame.positions.size());
    frame.positions.push_back(surface.positions[v]);
    frame.field.push_back(flow.smoothed_field.empty() ? 0.0 : flow.smoothed_field[v]);
    frame.drawn_field.push_back(flow.field[v]);
    frame.label.push_back(flow.label[v]);
  }
  frame.triangles = free_surface_faces(surface, surface_index);
  frame.vertex_faces = build_vertex_faces(frame.positions.size(), frame.triangles);
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
    const std::int8_t before =
        p >= 0
            ? region_sign(carried_value(previous.drawn_field.data(),
                                        closest_on_faces_around(previous, p, surface.positions[v])))
            : std::int8_t{FlowLabel::none};
    total += curvature.area[v];
    if (before != flow.label[v]) changed += curvature.area[v];
  }
  return total > 0.0 ? changed / total : 0.0;
}

void FlowCoherence::blend(const TriangleMesh& surface, std::span<const double> vertex_area,
                          const FlowRegions& flow, std::vector<double>& field,
                          std::vector<Vec3>& shading_normal) {
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
  carried_label_.resize(n);
  surface_index_.resize(n);
  turned_over_.resize(n);
  // The pending frame's bounding box, chunk by chunk, from the positions as they are copied:
  // the next frame's grid needs it, and a pass of its own would read them all again.
  std::vector<Box3> chunk_bounds(workers, Box3::of_no_points());
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    if (!any_surface) {
      std::fill(predecessor_.begin() + static_cast<std::ptrdiff_t>(begin),
                predecessor_.begin() + static_cast<std::ptrdiff_t>(end), -1);
      std::fill(surface_index_.begin() + static_cast<std::ptrdiff_t>(begin),
                surface_index_.begin() + static_cast<std::ptrdiff_t>(end), -1);
      std::fill(turned_over_.begin() + static_cast<std::ptrdiff_t>(begin),
                turned_over_.begin() + static_cast<std::ptrdiff_t>(end), 0);
      return;
    }
    // By plain pointers and values: the search is a call, after which the compiler would load
    // every member array's address again.
    const std::uint8_t* const on_surface = flow.free_surface.data();
    const Vec3* const position = surface.positions.data();
    const double* const field_before = previous_.field.data();
    const double* const drawn_before = previous_.drawn_field.data();
    const Vec3* const normal_before = previous_.shading_normal.data();
    const std::int8_t* const label_before = previous_.label.data();
    double* const s = field.data();
    std::int32_t* const predecessor = predecessor_.data();
    std::int8_t* const carried_label = carried_label_.data();
    std::int32_t* const surface_index = surface_index_.data();
    std::uint8_t* const turned_over = turned_over_.data();
    Vec3* const next_position = pending_.positions.data();
    const PointGrid* const previous_surface = grid ? &*grid : nullptr;
    const double blend = options_.blend, rise_blend = options_.rise_blend;
    const double normal_blend = options_.normal_blend;
    const double normal_change_limit = options_.normal_noise_multiple * flow.normal_noise;
    std::size_t next = chunk_begin[chunk];
    Box3 bounds =
        Box3::of_no_points();  // in a local: in the vector, each update would wait for a store
    for (std::size_t v = begin; v < end; ++v) {
      predecessor[v] = -1;
      carried_label[v] = FlowLabel::none;
      surface_index[v] = -1;
      turned_over[v] = 0;
      if (!on_surface[v]) continue;
      const std::int32_t p = previous_surface ? previous_surface->closest(position[v]) : -1;
      predecessor[v] = p;
      if (p >= 0) {
        const CarriedPoint from = closest_on_faces_around(previous_, p, position[v]);
        const double before = carried_value(field_before, from);
        carried_label[v] = region_sign(carried_value(drawn_before, from));
        const double now = s[v];
        // A field that grows (same sign, larger) is followed faster than one that fades, so a
        // crest that moves a cell or more a frame is not averaged away with the calm water it
        // has left.
        const double b = before * now > 0 && std::abs(now) > std::abs(before) ? rise_blend : blend;
        s[v] = (1 - b) * now + b * before;
        turned_over[v] = before * now < 0 && label_before[p] != FlowLabel::none;
        // Undefined normals (zero) are neither blended nor blended into.
        const auto& [a, b_, c] = from.corner;
        if (normals_before && normal_change_limit > 0.0 && shading_normal[v].squaredNorm() > 0.5 &&
            normal_before[a].squaredNorm() > 0.5 && normal_before[b_].squaredNorm() > 0.5 &&
            normal_before[c].squaredNorm() > 0.5) {
          const Vec3 carried = carried_value(normal_before, from);
          if (carried.squaredNorm() > 0.0) {
            const Vec3 normal = carried.normalized();
            const double change = (shading_normal[v] - normal).norm() / normal_change_limit;
            const double normal_weight = normal_blend * std::max(0.0, 1.0 - change * change);
            const Vec3 mixed = (1 - normal_weight) * shading_normal[v] + normal_weight * normal;
            if (mixed.squaredNorm() > 0.0) shading_normal[v] = mixed.normalized();
          }
        }
      }
      surface_index[v] = static_cast<std::int32_t>(next);
      next_position[next] = position[v];
      if (normals) pending_.shading_normal[next] = shading_normal[v];
      ++next;
      bounds.add(position[v]);
    }
    chunk_bounds[chunk] = bounds;
  });
  pending_bounds_ = Box3::of_no_points();
  for (const Box3& bounds : chunk_bounds) pending_bounds_.add(bounds);
  // The next frame carries its values from this frame's free surface.
  pending_.triangles = free_surface_faces(surface, surface_index_);
  pending_.vertex_faces = build_vertex_faces(pending_.positions.size(), pending_.triangles);
  if (grid) hold_dying_regions(surface, vertex_area, flow, field);
  std::size_t next = 0;
  for (std::size_t v = 0; v < n && any_surface; ++v)
    if (flow.free_surface[v]) pending_.field[next++] = field[v];
}

void FlowCoherence::hold_dying_regions(const TriangleMesh& surface,
                                       std::span<const double> vertex_area, const FlowRegions& flow,
                                       std::vector<double>& field) {
  if (std::find(turned_over_.begin(), turned_over_.end(), 1) == turned_over_.end()) return;
  const std::size_t n = field.size();
  // This frame's parts as the blend draws them, and the regions of the frame before that each
  // continues: a part continues a region of its sign that it overlaps (through the vertices'
  // predecessors), and a region's successors are all the parts that continue it.
  std::vector<std::int8_t> sign(n, FlowLabel::none);
  for (std::size_t v = 0; v < n; ++v)
    if (flow.free_surface[v]) sign[v] = region_sign(field[v]);
  const SignedParts parts = signed_parts(surface, sign, vertex_area);
  std::vector<std::pair<std::int32_t, std::int32_t>> continued;  // (part, region before)
  for (std::size_t v = 0; v < n; ++v) {
    const std::int32_t p = predecessor_[v];
    if (parts.part[v] >= 0 && p >= 0 && previous_.region[p] >= 0 && previous_.label[p] == sign[v])
      continued.emplace_back(parts.part[v], previous_.region[p]);
  }
  std::sort(continued.begin(), continued.end());
  continued.erase(std::unique(continued.begin(), continued.end()), continued.end());
  std::vector<double> successor_area(previous_.region_area.size(), 0.0);
  for (const auto& [part, region] : continued) successor_area[region] += parts.area[part];

  // Between b^−(k−1) and b^−k for k = turn_over_frames: a field held at it falls under the
  // threshold of 1 in the k-th frame after.
  const double b = options_.blend;
  const double cap = 0.5 * (std::pow(b, 1.0 - options_.turn_over_frames) +
                            std::pow(b, -static_cast<double>(options_.turn_over_frames)));
  for (std::size_t v = 0; v < n; ++v) {
    if (!turned_over_[v]) continue;
    const std::int32_t p = predecessor_[v], region = previous_.region[p];
    if (successor_area[region] >= options_.successor_share * previous_.region_area[region])
      continue;
    const double before = previous_.field[p];
    const double held = std::min(b * std::abs(before), cap);
    if (std::abs(field[v]) < held || field[v] * before < 0) field[v] = std::copysign(held, before);
  }
}

void FlowCoherence::remember(const TriangleMesh& surface, const CurvatureField& curvature,
                             const FlowRegions& flow) {
  // On one core, the areas summed in vertex order, so that the flicker does not depend on the
  // number of cores.
  double changed = 0.0, total = 0.0;
  if (flow.free_surface.size() == predecessor_.size()) {
    // By plain pointers: after the labels' byte stores the compiler would load every vector's
    // address again.
    const std::uint8_t* const on_surface = flow.free_surface.data();
    const std::int8_t *const label = flow.label.data(), *const before = carried_label_.data();
    const double* const area = curvature.area.data();
    std::int8_t* const next_label = pending_.label.data();
    const SignedParts regions = signed_parts(surface, flow.label, curvature.area);
    pending_.region.resize(pending_.label.size());
    pending_.region_area = regions.area;
    pending_.drawn_field.resize(pending_.label.size());
    std::size_t next = 0;
    for (std::size_t v = 0; v < predecessor_.size(); ++v) {
      if (!on_surface[v]) continue;
      total += area[v];
      if (label[v] != before[v]) changed += area[v];
      pending_.region[next] = regions.part[v];
      pending_.drawn_field[next] = flow.field[v];
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
  blend(surface, curvature.area, flow, field, flow.shading_normal);
  if (!first) label_flow_field(surface, curvature.area, std::move(field), flow);
  remember(surface, curvature, flow);
}

}  // namespace toonwater
