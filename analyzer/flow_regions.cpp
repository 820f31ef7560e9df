// Water-flow regions (You, Park, Choi, Noh, §2.3); the rules are stated in flow_regions.hpp.
#include "analyzer/flow_regions.hpp"

#include "analyzer/parallel.hpp"
#include "analyzer/topology.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace toonwater {

double median_edge_length(const TriangleMesh& mesh, std::size_t max_samples) {
  const std::size_t edge_count = 3 * mesh.triangles.size();
  if (edge_count == 0) return 0.0;
  const std::size_t stride = std::max<std::size_t>(1, edge_count / std::max<std::size_t>(1, max_samples));
  std::vector<double> lengths;
  lengths.reserve(edge_count / stride + 1);
  for (std::size_t e = 0; e < edge_count; e += stride) {
    const Triangle& t = mesh.triangles[e / 3];
    const int c = static_cast<int>(e % 3);
    const double length = (mesh.positions[t[(c + 1) % 3]] - mesh.positions[t[c]]).norm();
    if (length > 0.0 && std::isfinite(length)) lengths.push_back(length);
  }
  if (lengths.empty()) return 0.0;
  const auto middle = lengths.begin() + static_cast<std::ptrdiff_t>(lengths.size() / 2);
  std::nth_element(lengths.begin(), middle, lengths.end());
  return *middle;
}

namespace {

// A free-surface vertex: every incident face faces up (n·up above the limit), and so do all
// the faces of its neighbours. Walls and floor fail the first test; the second keeps one ring
// away from where they meet the water, which marching cubes rounds into a strongly curved
// fillet (in Mantaflow output its faces tilt 6°–65° off the vertical).
std::vector<std::uint8_t> free_surface_vertices(const TriangleMesh& mesh, const VertexFaces& vf,
                                                int up, double min_up_component) {
  std::vector<std::int8_t> face_up(mesh.triangles.size(), 0);  // 1 up, -1 not, 0 no normal
  parallel_chunks(mesh.triangles.size(), worker_count(mesh.triangles.size()),
                  [&](std::size_t, std::size_t begin, std::size_t end) {
                    for (std::size_t f = begin; f < end; ++f) {
                      const Triangle& t = mesh.triangles[f];
                      const Vec3& a = mesh.positions[t[0]];
                      const Vec3 cross = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a);
                      const double length = cross.norm();
                      if (length > 0.0 && std::isfinite(length))
                        face_up[f] = cross[up] > min_up_component * length ? 1 : -1;
                    }
                  });
  const std::size_t n = mesh.positions.size();
  std::vector<std::uint8_t> faces_up(n, 0);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      bool any_up = false, all_up = true;
      for (std::int32_t f : vf.of(static_cast<std::int32_t>(v))) {
        any_up |= face_up[f] > 0;
        all_up &= face_up[f] >= 0;
      }
      faces_up[v] = any_up && all_up;
    }
  });
  std::vector<std::uint8_t> free_surface(n, 0);
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      bool inside = faces_up[v];
      for (std::int32_t f : vf.of(static_cast<std::int32_t>(v)))
        for (std::int32_t w : mesh.triangles[f]) inside = inside && faces_up[w];
      free_surface[v] = inside;
    }
  });
  return free_surface;
}

// Median height of the selected vertices, from a deterministic sample of at most 100k.
double median_height(const TriangleMesh& mesh, const std::vector<std::uint8_t>& selected,
                     std::size_t selected_count, int up) {
  const std::size_t stride = std::max<std::size_t>(1, selected_count / 100000);
  std::vector<double> heights;
  heights.reserve(selected_count / stride + 1);
  std::size_t seen = 0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v)
    if (selected[v] && seen++ % stride == 0) heights.push_back(mesh.positions[v][up]);
  if (heights.empty()) return 0.0;
  const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
  std::nth_element(heights.begin(), middle, heights.end());
  return *middle;
}

// Bounding box of the free-surface vertices displaced from the rest level, grown by `margin`.
Box3 displaced_region(const TriangleMesh& mesh, const std::vector<std::uint8_t>& free_surface, int up,
                      double rest_height, double tolerance, double margin) {
  Box3 box;
  box.min = Vec3::Constant(std::numeric_limits<double>::infinity());
  box.max = -box.min;
  bool any = false;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!free_surface[v] || std::abs(mesh.positions[v][up] - rest_height) <= tolerance) continue;
    box.min = box.min.cwiseMin(mesh.positions[v]);
    box.max = box.max.cwiseMax(mesh.positions[v]);
    any = true;
  }
  if (!any) return Box3{};
  box.min.array() -= margin;
  box.max.array() += margin;
  return box;
}

}  // namespace

FlowRegions find_flow_regions(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                              const CurvatureField& curvature, const FlowOptions& options) {
  const int up = static_cast<int>(options.up);
  FlowRegions flow;
  flow.label.assign(mesh.positions.size(), FlowLabel::none);
  flow.median_edge_length = median_edge_length(mesh);
  const double edge = flow.median_edge_length;
  flow.threshold = options.k_threshold.value_or(
      edge > 0.0 ? options.k_threshold_relative / (edge * edge) : 0.0);

  const std::vector<std::uint8_t> free_surface =
      free_surface_vertices(mesh, vertex_faces, up, options.min_up_component);
  flow.free_surface_vertices =
      static_cast<std::size_t>(std::count(free_surface.begin(), free_surface.end(), 1));
  flow.rest_height = options.rest_height.value_or(
      median_height(mesh, free_surface, flow.free_surface_vertices, up));
  if (options.region_of_interest) {
    flow.region_of_interest =
        displaced_region(mesh, free_surface, up, flow.rest_height,
                         options.displacement_tolerance * edge, options.margin * edge);
  } else if (!mesh.positions.empty()) {
    flow.region_of_interest.min = flow.region_of_interest.max = mesh.positions[0];
    for (const Vec3& p : mesh.positions) {
      flow.region_of_interest.min = flow.region_of_interest.min.cwiseMin(p);
      flow.region_of_interest.max = flow.region_of_interest.max.cwiseMax(p);
    }
  }
  if (flow.threshold <= 0.0 || flow.region_of_interest.empty()) return flow;

  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!free_surface[v] || curvature.status[v] == CurvatureStatus::undefined) continue;
    if (std::abs(curvature.gaussian[v]) <= flow.threshold) continue;
    if (!flow.region_of_interest.contains(mesh.positions[v])) continue;
    if (curvature.mean[v] > 0.0) {
      flow.label[v] = FlowLabel::ridge;
      ++flow.ridge_vertices;
    } else if (curvature.mean[v] < 0.0) {
      flow.label[v] = FlowLabel::valley;
      ++flow.valley_vertices;
    }
  }
  return flow;
}

}  // namespace toonwater
