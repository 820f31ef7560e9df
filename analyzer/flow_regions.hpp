// Water-flow regions: where an animator draws the crests (ridges) and troughs (valleys) of the
// water, after You, Park, Choi, Noh, "Toon Rendering of Water Animation" (§2.3).
//
// Each free-surface vertex gets a continuous signed flow field s, positive on ridges; a region
// is where |s| >= 1. Two criteria:
//   mean   (default)  s = H / T          T in 1/length
//   paper             s = sign(H)·|K| / T  T in 1/length²   (the paper's ridge |K| > T, H > 0)
// Why H by default: on a crest or trough that is round in plan (a ripple ring) one principal
// curvature is about 0, so K = k1·k2 vanishes on the very circle an animator draws and |K| can
// at best catch the flanks of steep waves; H = (k1 + k2)/2 is largest there, and its sign tells
// crest (H > 0, normals up) from trough. H is also near 0 on a saddle where a crest crosses a
// trough, so the sign never flips on a region that is drawn.
//
// The threshold is tied to the scene, never to the mesh: T = c / L (mean) or c / L² (paper),
// with L = sqrt(free-surface area) (the mixed Voronoi areas summed). A converged surface
// keeps its regions under refinement and the same scene in millimetres or metres gets the same
// vertices, as K ∝ 1/s² and H ∝ 1/s.
//
// Then, in this order:
//   1. smoothing: `smoothing_steps` Jacobi steps of the area-weighted one-ring mean of s over
//      the free surface (curvature_smoothing.hpp), which damps the vertex-to-vertex noise of the
//      cotangent curvature on marching-cubes meshes;
//   2. over a sequence, blending with the previous frame (flow_coherence.hpp);
//   3. fading: a region (connected free-surface vertices with s >= 1, or s <= −1) whose area is
//      below A_min (a speck) or whose peak |s| is barely 1 fades out: s is scaled down until
//      its peak is below 1 (so it is not drawn), and regions between A_min and 2 A_min, or with
//      a peak between 1 and 1.5, are scaled part way. A region that is born starts at a point
//      and grows, one that dies shrinks to a point: nothing pops. A_min is in scene units²,
//      0.002 L² by default; A_min = 0 turns the fading off;
//   4. labels: +1 where s >= 1, −1 where s <= −1, else 0.
// The field written out (texture coordinates, CSV, PLY) is the one labels are taken from, so
// POV-Ray, interpolating s inside each triangle and cutting it at ±1 per pixel, draws smooth
// region boundaries that agree with the labels at the vertices.
//
// Labels are set only on the free surface (free_surface.hpp). The paper restricts its work to a
// region of interest around displaced water; here the whole free surface costs a few
// milliseconds, so no region is ever cut off: `region_of_interest` reports the bounding box of
// the regions.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/edge_length.hpp"
#include "analyzer/free_surface.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace toonwater {

enum class FlowCriterion : std::uint8_t { mean, paper };

// The criterion's defaults: c in T = c / L (mean) or c / L² (paper), L = sqrt(free-surface
// area); smoothing steps; A_min / L².
struct FlowDefaults {
  double threshold_relative;
  int smoothing_steps;
  double min_region_relative;
};
FlowDefaults flow_defaults(FlowCriterion criterion);

// The free-surface selection's settings (free_surface.hpp, the up axis among them), then the
// flow field's.
struct FlowOptions : FreeSurfaceOptions {
  FlowCriterion criterion = FlowCriterion::mean;
  std::optional<double> threshold;           // absolute T; overrides threshold_relative
  std::optional<double> threshold_relative;  // c; default: default_threshold_relative(criterion)
  // Unset, these take the criterion's defaults: for mean 2 steps and A_min = 0.002 L²; for
  // paper none and none, so that it stays the paper's rule.
  std::optional<int> smoothing_steps;        // Jacobi steps over the free surface
  std::optional<double> min_region_area;     // absolute A_min (scene units²)
};

enum FlowLabel : std::int8_t { valley = -1, none = 0, ridge = 1 };

struct FlowRegions {
  std::vector<double> field;       // per vertex: s (0 off the free surface); regions at |s| >= 1
  std::vector<double> smoothed_field;  // s after step 1, before coherence and fading
  std::vector<std::int8_t> label;  // per vertex: FlowLabel
  FlowCriterion criterion = FlowCriterion::mean;
  double threshold = 0.0;          // T actually used
  double scale_length = 0.0;       // L = sqrt(free-surface area)
  double min_region_area = 0.0;    // A_min actually used
  double median_edge_length = 0.0;
  double rest_height = 0.0;
  Box3 region_of_interest;         // bounding box of the regions; empty when there are none
  std::vector<std::uint8_t> free_surface;  // per vertex: 1 on the free surface (free_surface.hpp)
  std::size_t free_surface_vertices = 0;
  std::size_t free_surface_patches_dropped = 0;
  std::size_t ridge_vertices = 0;
  std::size_t valley_vertices = 0;
  std::size_t regions = 0;         // drawn regions (connected, one sign)
  std::size_t specks_faded = 0;    // regions faded in part or whole
};

class FlowCoherence;

// With `coherence` (a sequence's state, flow_coherence.hpp), step 2 blends this frame's field
// with the frames it saw before.
FlowRegions find_flow_regions(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                              const CurvatureField& curvature, const FlowOptions& options,
                              FlowCoherence* coherence = nullptr);

// Steps 3 and 4 of the header on `field` (s before the fading, after coherence for example):
// fades the specks, then sets flow.field, the labels, the counts and the region of interest.
void label_flow_field(const TriangleMesh& mesh, std::span<const double> vertex_area,
                      std::vector<double> field, FlowRegions& flow);

}  // namespace toonwater
