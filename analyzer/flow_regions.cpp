// Water-flow regions; the field, its threshold and the steps are stated in flow_regions.hpp.
#include "analyzer/flow_regions.hpp"

#include "analyzer/curvature_smoothing.hpp"
#include "analyzer/disjoint_sets.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/free_surface.hpp"
#include "analyzer/noise_floor.hpp"
#include "analyzer/tank_walls.hpp"
#include "common/deterministic_sum.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

namespace toonwater {

// Chosen on real simulation output and analytic ripples (docs/analyzer.md, "Water-flow regions").
// With mean:
// - c = 2: a long crest is drawn where its radius of curvature 1/(2H) is below L/4 (the wake
//   and bow wave of a Mantaflow basin; a ripple ring 0.5 % of the scene's size high and 15 %
//   long on its crest and trough circles);
// - z = 3: H must also stand 3 noise floors above the calm water (Gaussian noise passes that at
//   0.3 % of the vertices, isolated ones the area limit fades); with 4 an FFT ocean, whose chop
//   counts as noise, kept no crest at all;
// - the field's smoothing, 0.8 edge lengths (2 steps), damps the vertex-to-vertex noise of the
//   cotangent H and keeps analytic ripples 12 cells long alike at every resolution (1.25 edge
//   lengths lost 40 % of their area at 81²); the noise floor does the rest;
// - the shading normals' smoothing, 1.5 edge lengths (7 steps), spans the marching-cubes jitter
//   of a level set's surface, whose wavelength is about two cells;
// - the walls' strip, 3 edge lengths and a ramp as wide again, covers the 2–3 cells over which
//   a Mantaflow tank's surface droops into its walls;
// - nothing fades along the free surface's other borders: the crest of a bore or a wave beside
//   its steep front is what an animator draws at an impact (a fade over 1-3 edge lengths there
//   lost the dam break's bore as it hit the sphere);
// - 6 regions are what an animator draws on one water surface: the impact, the crown, a few
//   rings and waves.
// With paper, the value that labels about the same share of the Mantaflow basin as the paper's
// rule (T = 0.01/ℓ²) did at its resolution, and nothing else (the shading normals are smoothed
// alike: they are the scene's, whatever the criterion).
FlowDefaults flow_defaults(FlowCriterion criterion) {
  if (criterion == FlowCriterion::mean) return {2.0, 0.8, 1.5, 0.002, 3.0, 3.0, 6.0, 6};
  return {30.0, 0.0, 1.5, 0.0, 0.0, 0.0, 0.0, 0};
}

int smoothing_steps_for_radius(double radius_in_edge_lengths) {
  return static_cast<int>(std::ceil(3.0 * radius_in_edge_lengths * radius_in_edge_lengths));
}

std::int8_t region_sign(double s) {
  return s >= 1.0 ? FlowLabel::ridge : s <= -1.0 ? FlowLabel::valley : FlowLabel::none;
}

namespace {

// How much of a region's field survives the fading: the smaller of two factors, each 1 for a
// region well above the limits and falling to the one that brings the region's peak |s| just
// under 1 (where it is no longer drawn) at the limit:
//   by area: from 2 A_min (1) down to A_min (hidden);
//   by peak: from a peak of 1 + peak_ramp (1) down to 1 (hidden).
// So a region that is born (its peak crossing 1, its area growing) starts at a point and grows,
// and one that dies shrinks to a point: a broad crest whose peak crosses the threshold would
// otherwise appear at once over its whole flat top.
constexpr double peak_ramp = 0.5;

// `salience_cut`: the salience of the most salient region left out by max_regions (0: none is);
// by salience: from twice it (1) down to it (hidden).
double fade_factor(double area, double peak, double min_area, double salience,
                   double salience_cut) {
  constexpr double just_below_one = 0.999;
  const double hidden = just_below_one / peak;
  const double by_area = min_area > 0.0 ? std::clamp((area - min_area) / min_area, 0.0, 1.0) : 1.0;
  const double by_peak = min_area > 0.0 ? std::clamp((peak - 1.0) / peak_ramp, 0.0, 1.0) : 1.0;
  // A cut of +inf (saliences beyond the doubles) leaves no region, as any larger one would.
  const double by_salience = !(salience_cut > 0.0) ? 1.0
                             : std::isinf(salience_cut)
                                 ? (std::isinf(salience) ? 1.0 : 0.0)
                                 : std::clamp((salience - salience_cut) / salience_cut, 0.0, 1.0);
  return hidden + (1.0 - hidden) * std::min({by_area, by_peak, by_salience});
}

}  // namespace

void label_flow_field(const TriangleMesh& mesh, std::span<const double> vertex_area,
                      std::vector<double> field, FlowRegions& flow) {
  const std::size_t n = field.size();
  flow.label.assign(n, FlowLabel::none);
  flow.ridge_vertices = flow.valley_vertices = flow.regions = flow.specks_faded = 0;
  flow.region_of_interest = Box3{};
  const std::size_t workers = chunk_count(n);

  // The vertices in regions, numbered compactly in vertex order: regions are a small part of
  // the surface. Counted chunk by chunk, then numbered from each chunk's offset. (The arrays are
  // left uninitialised by new: every slot read is written first; member_index only at the
  // members, the only slots the joins read.)
  std::unique_ptr<std::int32_t[]> member_index(new std::int32_t[n]);
  std::unique_ptr<std::int8_t[]> sign(new std::int8_t[n]);
  std::vector<std::int32_t> chunk_begin(workers + 1, 0);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    // By plain pointers: after a byte store the compiler would load a vector's address again.
    const double* const s = field.data();
    std::int8_t* const sign_of = sign.get();
    std::int32_t count = 0;
    for (std::size_t v = begin; v < end; ++v) {
      sign_of[v] = region_sign(s[v]);
      count += sign_of[v] != FlowLabel::none;
    }
    chunk_begin[chunk + 1] = count;
  });
  std::partial_sum(chunk_begin.begin(), chunk_begin.end(), chunk_begin.begin());
  const std::size_t m = static_cast<std::size_t>(chunk_begin.back());
  std::unique_ptr<std::int32_t[]> members(new std::int32_t[m]);
  parallel_chunks(n, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    std::int32_t next = chunk_begin[chunk];
    for (std::size_t v = begin; v < end; ++v) {
      if (sign[v] == FlowLabel::none) continue;
      member_index[v] = next;
      members[next++] = static_cast<std::int32_t>(v);
    }
  });
  // Regions: vertices of one sign joined along the edges between them. The signs are a byte a
  // vertex, so the pass over the faces, most of which touch no region, stays in cache.
  DisjointSets sets(m);
  const std::size_t face_chunks = m > 0 ? chunk_count(mesh.triangles.size()) : 1;
  std::vector<std::int32_t> range_begin = vertex_ranges(mesh.triangles, n, face_chunks);
  for (std::int32_t& begin : range_begin)  // vertex ranges to member ranges
    begin = static_cast<std::int32_t>(std::lower_bound(members.get(), members.get() + m, begin) -
                                      members.get());
  join_in_parallel(sets, mesh.triangles.size(), range_begin, [&](std::size_t f, auto& join) {
    const Triangle& t = mesh.triangles[f];
    const std::int8_t s0 = sign[t[0]], s1 = sign[t[1]], s2 = sign[t[2]];
    if ((s0 | s1 | s2) == 0) return;
    // A face of one sign is joined by two of its edges; its third would add nothing.
    if (s0 != FlowLabel::none && s0 == s1) join(member_index[t[0]], member_index[t[1]]);
    if (s1 != FlowLabel::none && s1 == s2) join(member_index[t[1]], member_index[t[2]]);
    if (s2 != FlowLabel::none && s2 == s0 && s0 != s1) join(member_index[t[2]], member_index[t[0]]);
  });
  // Each region's figures sit in the slot of its root; the other slots are never touched (nor
  // their pages faulted in: `new` leaves them uninitialised).
  struct Region {
    double area, peak, salience, factor;
  };
  std::unique_ptr<Region[]> region(new Region[m]);
  std::unique_ptr<std::int32_t[]> region_of(new std::int32_t[m]);
  parallel_chunks(m, chunk_count(m), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      region_of[i] = sets.root_of(static_cast<std::int32_t>(i));
      if (region_of[i] == static_cast<std::int32_t>(i)) region[i] = Region{0.0, 0.0, 0.0, 1.0};
    }
  });
  // Areas summed in vertex order, so that they do not depend on the core count.
  std::vector<std::int32_t> roots;
  for (std::size_t i = 0; i < m; ++i) {
    Region& r = region[region_of[i]];
    r.area += vertex_area[members[i]];
    r.peak = std::max(r.peak, std::abs(field[members[i]]));
    r.salience += vertex_area[members[i]] * (std::abs(field[members[i]]) - 1.0);
    if (region_of[i] == static_cast<std::int32_t>(i)) roots.push_back(static_cast<std::int32_t>(i));
  }
  double salience_cut = 0.0;
  if (flow.max_regions > 0 && roots.size() > flow.max_regions) {
    std::vector<double> saliences;
    for (std::int32_t root : roots) saliences.push_back(region[root].salience);
    const auto cut = saliences.begin() + static_cast<std::ptrdiff_t>(flow.max_regions);
    std::nth_element(saliences.begin(), cut, saliences.end(), std::greater<>());
    salience_cut = *cut;
  }
  for (std::int32_t root : roots) {
    Region& r = region[root];
    if (flow.min_region_area > 0.0 || salience_cut > 0.0)
      r.factor = fade_factor(r.area, r.peak, flow.min_region_area, r.salience, salience_cut);
    flow.specks_faded += r.factor < 1.0;
    flow.regions += r.factor * r.peak >= 1.0;
  }

  // The faded field and the labels, chunk by chunk, each with its own counts and box.
  struct Tally {
    std::size_t ridges = 0, valleys = 0;
    Box3 box = Box3::of_no_points();
  };
  const std::size_t member_workers = chunk_count(m);
  std::vector<Tally> tallies(member_workers);
  parallel_chunks(m, member_workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    Tally tally;  // in a local: in the vector, each update would wait for the last one's store
    double* const s = field.data();  // plain pointers again: the labels are byte stores
    std::int8_t* const label_of = flow.label.data();
    const Vec3* const positions = mesh.positions.data();
    for (std::size_t i = begin; i < end; ++i) {
      const std::int32_t v = members[i];
      s[v] *= region[region_of[i]].factor;
      const std::int8_t label = region_sign(s[v]);
      label_of[v] = label;
      if (label == FlowLabel::none) continue;
      tally.ridges += label == FlowLabel::ridge;
      tally.valleys += label == FlowLabel::valley;
      tally.box.add(positions[v]);
    }
    tallies[chunk] = tally;
  });
  Box3& box = flow.region_of_interest;
  box = Box3::of_no_points();
  for (const Tally& tally : tallies) {
    flow.ridge_vertices += tally.ridges;
    flow.valley_vertices += tally.valleys;
    box.add(tally.box);
  }
  if (flow.ridge_vertices + flow.valley_vertices == 0) box = Box3{};
  flow.field = std::move(field);
}

namespace {

// Step 1 of flow_regions.hpp on the shading normals: the curvature normals smoothed over every
// vertex whose curvature is defined (crowns, sheets and droplets have toon bands too), then,
// where they face up (the free surface and the top of the rounded rim along a wall), tilted
// back towards up by the walls' weight; unit length. `noise`: the noise floor of their
// horizontal components on the calm part (`member`), the RMS of the two (noise_floor.hpp).
std::vector<Vec3> shading_normals(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                  const CurvatureField& curvature,
                                  std::span<const std::uint8_t> member,
                                  std::span<const double> wall_weight, Axis up, int steps,
                                  double& noise) {
  const std::size_t n = mesh.positions.size();
  const int u = static_cast<int>(up);
  std::vector<std::uint8_t> defined(n);
  for (std::size_t v = 0; v < n; ++v)
    defined[v] = curvature.status[v] != CurvatureStatus::undefined;
  std::vector<Vec3> normal = curvature.normal;
  smooth_vertex_field(mesh, vertex_faces, curvature.area, defined, normal, steps);
  const double gain =
      smoothing_noise_gain(mesh, vertex_faces, curvature.area, defined, member, steps);
  std::vector<double> raw(n), smoothed(n);
  double noise_squares = 0.0;
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == u) continue;
    for (std::size_t v = 0; v < n; ++v) {
      raw[v] = curvature.normal[v][axis];
      smoothed[v] = normal[v][axis];
    }
    const double floor = smoothed_noise_floor(raw, smoothed, member, gain);
    noise_squares += 0.5 * floor * floor;
  }
  noise = std::sqrt(noise_squares);
  Vec3 up_vector = Vec3::Zero();
  up_vector[u] = 1.0;
  for (std::size_t v = 0; v < n; ++v) {
    if (!defined[v]) continue;
    const double length = normal[v].norm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      normal[v] = curvature.normal[v];
      continue;
    }
    normal[v] /= length;
    if (normal[v][u] <= free_surface_min_up_component) continue;
    normal[v] = (wall_weight[v] * normal[v] + (1.0 - wall_weight[v]) * up_vector).normalized();
  }
  return normal;
}

}  // namespace

FlowRegions find_flow_regions(const TriangleMesh& mesh, const MeshTopology& topology,
                              const CurvatureField& curvature, const FlowOptions& options,
                              FlowCoherence* coherence) {
  const VertexFaces& vertex_faces = topology.vertex_faces;
  const std::size_t n = mesh.positions.size();
  FlowRegions flow;
  flow.criterion = options.criterion;
  FreeSurface surface = select_free_surface(mesh, options);
  flow.median_edge_length = surface.edge_length;
  flow.free_surface = std::move(surface.selected);
  flow.free_surface_vertices = surface.vertices;
  flow.free_surface_patches_dropped = surface.patches_dropped;
  flow.rest_height = surface.rest_height;

  // The vertices that carry the field: free surface, curvature defined, and not on the free
  // surface's border, where marching cubes rounds the water into a wall (a fillet one or two
  // cells wide, as curved as a crest but no flow line).
  std::vector<std::uint8_t> member = std::move(surface.inside);
  for (std::size_t v = 0; v < n; ++v)
    member[v] = member[v] && curvature.status[v] != CurvatureStatus::undefined;
  const double surface_area =
      deterministic_sum(n, [on_surface = flow.free_surface.data(), status = curvature.status.data(),
                            area = curvature.area.data()](std::size_t v) {
        return on_surface[v] && status[v] != CurvatureStatus::undefined ? area[v] : 0.0;
      });
  flow.scale_length = std::sqrt(surface_area);
  const double length = flow.scale_length;
  const FlowDefaults defaults = flow_defaults(options.criterion);
  const bool paper = options.criterion == FlowCriterion::paper;
  flow.min_region_area =
      options.min_region_area.value_or(defaults.min_region_relative * surface_area);
  flow.max_regions = defaults.max_regions;
  const int steps =
      options.smoothing_steps.value_or(smoothing_steps_for_radius(defaults.smoothing_radius));

  // The tank's walls (step 2), for the field and the shading normals.
  const bool closed = topology.boundary_edges == 0 && topology.nonmanifold_edges == 0;
  const TankWalls walls =
      closed ? find_tank_walls(mesh, options.up, flow.median_edge_length) : TankWalls{};
  flow.walls = walls.count();
  const std::vector<double> wall_weight =
      wall_weights(mesh, options.up, walls, defaults.wall_near * flow.median_edge_length,
                   defaults.wall_far * flow.median_edge_length);
  // The shading normals before the field: their smoothing, of vectors, is the analysis's
  // largest allocation, and the field and its copy need not be held beside it.
  if (options.shading_normals)
    flow.shading_normal =
        shading_normals(mesh, vertex_faces, curvature, member, wall_weight, options.up,
                        smoothing_steps_for_radius(defaults.shading_radius), flow.normal_noise);

  // The field's source, smoothed (step 1): H, or the paper's sign(H)·|K|.
  std::vector<double> field(n, 0.0);
  for (std::size_t v = 0; v < n; ++v) {
    if (!member[v]) continue;
    const double mean = curvature.mean[v];
    // Only H = 0 exactly (or −0) gives the paper's field the sign of zero: it is not a region.
    const double value =
        paper ? (mean == 0.0 ? 0.0 : std::copysign(std::abs(curvature.gaussian[v]), mean)) : mean;
    field[v] = std::isfinite(value) ? value : 0.0;
  }
  {
    const std::vector<double> raw = field;
    smooth_vertex_field(mesh, vertex_faces, curvature.area, member, field, steps);
    // The threshold, held above the noise floor unless given.
    flow.noise_floor = smoothed_noise_floor(
        raw, field, member,
        smoothing_noise_gain(mesh, vertex_faces, curvature.area, member, member, steps));
  }
  flow.sequence_noise_floor =
      coherence ? coherence->sequence_noise_floor(flow.noise_floor) : flow.noise_floor;
  const double c = options.threshold_relative.value_or(defaults.threshold_relative);
  const double scene_threshold = length > 0.0 ? (paper ? c / (length * length) : c / length) : 0.0;
  const bool explicit_threshold = options.threshold || options.threshold_relative;
  flow.threshold = options.threshold.value_or(
      explicit_threshold
          ? scene_threshold
          : std::max(scene_threshold, defaults.noise_multiple * flow.sequence_noise_floor));

  if (flow.threshold > 0.0 && std::isfinite(flow.threshold)) {
    for (std::size_t v = 0; v < n; ++v) {
      field[v] = member[v] ? field[v] / flow.threshold * wall_weight[v] : 0.0;
      if (!std::isfinite(field[v])) field[v] = 0.0;
    }
  } else {
    std::fill(field.begin(), field.end(), 0.0);
  }
  flow.smoothed_field = field;
  if (coherence) coherence->blend(mesh, curvature.area, flow, field, flow.shading_normal);
  label_flow_field(mesh, curvature.area, std::move(field), flow);
  if (coherence) coherence->remember(mesh, curvature, flow);
  return flow;
}

}  // namespace toonwater
