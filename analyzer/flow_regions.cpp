// Water-flow regions (You, Park, Choi, Noh, §2.3); the rules are stated in flow_regions.hpp.
#include "analyzer/flow_regions.hpp"

#include "analyzer/free_surface.hpp"

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

  FreeSurfaceOptions surface_options;
  surface_options.up = options.up;
  surface_options.min_up_component = options.min_up_component;
  surface_options.rest_height = options.rest_height;
  surface_options.max_depth = options.max_depth;
  surface_options.min_patch_vertices = options.min_patch_vertices;
  FreeSurface surface = select_free_surface(mesh, vertex_faces, edge, surface_options);
  flow.free_surface = std::move(surface.selected);
  flow.free_surface_vertices = surface.vertices;
  flow.free_surface_patches_dropped = surface.patches_dropped;
  flow.rest_height = surface.rest_height;
  const std::vector<std::uint8_t>& free_surface = flow.free_surface;
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
