// Water-flow regions; the field, its threshold and the steps are stated in flow_regions.hpp.
#include "analyzer/flow_regions.hpp"

#include "analyzer/curvature_smoothing.hpp"
#include "analyzer/disjoint_sets.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/free_surface.hpp"
#include "common/ordered_sum.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

namespace toonwater {

// Chosen on real simulation output and analytic ripples (README, "Water-flow regions"): with
// mean, a long crest is drawn where its radius of curvature 1/(2H) is below L/4 (the wake and
// bow wave of a Mantaflow basin, a ripple ring 0.5 % of the scene's size high and 15 % long on
// its crest and trough circles; calm water and the marching-cubes noise on it are not); with
// paper, the value that labels about the same share of the Mantaflow basin as the paper's rule
// (T = 0.01/ℓ²) did at its resolution.
FlowDefaults flow_defaults(FlowCriterion criterion) {
  if (criterion == FlowCriterion::mean) return {2.0, 2, 0.002};
  return {30.0, 0, 0.0};
}

namespace {

// The sign of s as a region sees it: ±1 inside a region, 0 outside.
std::int8_t region_sign(double s) {
  return s >= 1.0 ? FlowLabel::ridge : s <= -1.0 ? FlowLabel::valley : FlowLabel::none;
}

// How much of a region's field survives the fading: the smaller of two factors, each 1 for a
// region well above the limits and falling to the one that brings the region's peak |s| just
// under 1 (where it is no longer drawn) at the limit:
//   by area: from 2 A_min (1) down to A_min (hidden);
//   by peak: from a peak of 1 + peak_ramp (1) down to 1 (hidden).
// So a region that is born (its peak crossing 1, its area growing) starts at a point and grows,
// and one that dies shrinks to a point: a broad crest whose peak crosses the threshold would
// otherwise appear at once over its whole flat top.
constexpr double peak_ramp = 0.5;

double fade_factor(double area, double peak, double min_area) {
  constexpr double just_below_one = 0.999;
  const double hidden = just_below_one / peak;
  const double by_area = std::clamp((area - min_area) / min_area, 0.0, 1.0);
  const double by_peak = std::clamp((peak - 1.0) / peak_ramp, 0.0, 1.0);
  return hidden + (1.0 - hidden) * std::min(by_area, by_peak);
}

}  // namespace

void label_flow_field(const TriangleMesh& mesh, std::span<const double> vertex_area,
                      std::vector<double> field, FlowRegions& flow) {
  const std::size_t n = field.size();
  flow.label.assign(n, FlowLabel::none);
  flow.ridge_vertices = flow.valley_vertices = flow.regions = flow.specks_faded = 0;
  flow.region_of_interest = Box3{};
  const std::size_t workers = worker_count(n);

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
  const std::size_t face_chunks = m > 0 ? worker_count(mesh.triangles.size()) : 1;
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
    double area, peak, factor;
  };
  std::unique_ptr<Region[]> region(new Region[m]);
  std::unique_ptr<std::int32_t[]> region_of(new std::int32_t[m]);
  parallel_chunks(m, worker_count(m), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      region_of[i] = sets.root_of(static_cast<std::int32_t>(i));
      if (region_of[i] == static_cast<std::int32_t>(i)) region[i] = Region{0.0, 0.0, 1.0};
    }
  });
  // Areas summed in vertex order, so that they do not depend on the core count.
  std::vector<std::int32_t> roots;
  for (std::size_t i = 0; i < m; ++i) {
    Region& r = region[region_of[i]];
    r.area += vertex_area[members[i]];
    r.peak = std::max(r.peak, std::abs(field[members[i]]));
    if (region_of[i] == static_cast<std::int32_t>(i)) roots.push_back(static_cast<std::int32_t>(i));
  }
  for (std::int32_t root : roots) {
    Region& r = region[root];
    if (flow.min_region_area > 0.0) r.factor = fade_factor(r.area, r.peak, flow.min_region_area);
    flow.specks_faded += r.factor < 1.0;
    flow.regions += r.factor * r.peak >= 1.0;
  }

  // The faded field and the labels, chunk by chunk, each with its own counts and box.
  struct Tally {
    std::size_t ridges = 0, valleys = 0;
    Box3 box = Box3::of_no_points();
  };
  const std::size_t member_workers = worker_count(m);
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

FlowRegions find_flow_regions(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                              const CurvatureField& curvature, const FlowOptions& options,
                              FlowCoherence* coherence) {
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
  const std::size_t workers = worker_count(n);
  const double surface_area = ordered_sum(
      n, [on_surface = flow.free_surface.data(), status = curvature.status.data(),
          area = curvature.area.data()](std::size_t v) {
        return on_surface[v] && status[v] != CurvatureStatus::undefined ? area[v] : 0.0;
      });
  flow.scale_length = std::sqrt(surface_area);
  const double length = flow.scale_length;
  const FlowDefaults defaults = flow_defaults(options.criterion);
  const double c = options.threshold_relative.value_or(defaults.threshold_relative);
  flow.threshold = options.threshold.value_or(
      length > 0.0 ? (options.criterion == FlowCriterion::mean ? c / length : c / (length * length))
                   : 0.0);
  flow.min_region_area = options.min_region_area.value_or(defaults.min_region_relative * surface_area);

  std::vector<double> field(n, 0.0);
  if (flow.threshold > 0.0 && std::isfinite(flow.threshold)) {
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      std::uint8_t* const carries = member.data();  // plain pointers: it is a byte store
      const CurvatureStatus* const status = curvature.status.data();
      const double *const mean_of = curvature.mean.data(), *const gaussian_of = curvature.gaussian.data();
      double* const s = field.data();
      const bool paper = options.criterion == FlowCriterion::paper;
      const double threshold = flow.threshold;
      for (std::size_t v = begin; v < end; ++v) {
        // Where the curvature is undefined there is no field, and no weight in the smoothing.
        carries[v] = carries[v] && status[v] != CurvatureStatus::undefined;
        if (!carries[v]) continue;
        const double mean = mean_of[v];
        const double value = paper ? std::copysign(std::abs(gaussian_of[v]), mean) / threshold
                                   : mean / threshold;
        // Only H = 0 exactly (or −0) gives the paper's field the sign of zero: it is not a region.
        s[v] = paper && mean == 0.0 ? 0.0 : value;
        if (!std::isfinite(s[v])) s[v] = 0.0;
      }
    });
    smooth_vertex_field(mesh, vertex_faces, curvature.area, member, field,
                        options.smoothing_steps.value_or(defaults.smoothing_steps));
  }
  flow.smoothed_field = field;
  if (coherence) coherence->blend(mesh, flow, field);
  label_flow_field(mesh, curvature.area, std::move(field), flow);
  if (coherence) coherence->remember(curvature, flow);
  return flow;
}

}  // namespace toonwater
