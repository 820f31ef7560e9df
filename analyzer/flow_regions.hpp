// Water-flow regions (You, Park, Choi, Noh, "Toon Rendering of Water Animation", §2.3):
//   ridge  where |K| > T and H > 0,
//   valley where |K| > T and H < 0,
// marked only on the free surface (free_surface.hpp: not on the walls, floor and corners of a
// closed liquid volume, nor on the fillets where they meet the water or the floor of a cavity
// under a floating object) and only inside a region of interest: the bounding box of the
// free-surface vertices displaced from the water's rest level, grown by a margin.
//
// Scale-free defaults: lengths are measured in median edge lengths ℓ, and the default threshold
// is T = c / ℓ² (K has units 1/length²), so the same scene in millimetres or in metres gets the
// same regions.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace toonwater {

struct FlowOptions {
  Axis up = Axis::y;
  std::optional<double> k_threshold;       // absolute T; overrides k_threshold_relative
  double k_threshold_relative = 0.01;      // c in T = c / ℓ²
  bool region_of_interest = true;          // false: label every free-surface vertex
  std::optional<double> rest_height;       // default: median height of the upward-facing vertices
  double displacement_tolerance = 0.5;     // in ℓ: |height − rest| above this is "displaced"
  double margin = 3.0;                     // in ℓ: growth of the displaced vertices' box
  // Free-surface selection: see free_surface.hpp.
  double min_up_component = 0.5;           // a free-surface face has n·up above this (slope < 60°)
  double max_depth = 2.0;                  // in ℓ: patches deeper below the rest level are dropped
  std::size_t min_patch_vertices = 16;     // smaller detached patches (droplets) carry no flow
};

struct Box3 {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(-1.0);  // empty by default
  bool empty() const { return (max.array() < min.array()).any(); }
  bool contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
};

enum FlowLabel : std::int8_t { valley = -1, none = 0, ridge = 1 };

struct FlowRegions {
  std::vector<std::int8_t> label;  // per vertex: FlowLabel
  double threshold = 0.0;          // T actually used
  double median_edge_length = 0.0;
  double rest_height = 0.0;
  Box3 region_of_interest;         // empty when nothing is displaced
  std::vector<std::uint8_t> free_surface;  // per vertex: 1 on the free surface (free_surface.hpp)
  std::size_t free_surface_vertices = 0;
  std::size_t free_surface_patches_dropped = 0;
  std::size_t ridge_vertices = 0;
  std::size_t valley_vertices = 0;
};

// Median edge length, from a deterministic sample of at most `max_samples` edges.
double median_edge_length(const TriangleMesh& mesh, std::size_t max_samples = 100000);

FlowRegions find_flow_regions(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                              const CurvatureField& curvature, const FlowOptions& options);

}  // namespace toonwater
