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
// The threshold is tied to the scene and held above the data's own noise, never tied to the
// mesh's resolution:
//   T = max(c / L, z σ)          (mean, z = 3; paper: c / L², no noise floor)
// with L = sqrt(free-surface area) (the mixed Voronoi areas summed) and σ the noise floor of
// the smoothed field H on the free surface (robust_spread.hpp: its lower-quartile spread, which
// the calm water sets), taken over the frames seen so far in a sequence (their median). A
// converged surface keeps its regions under refinement and the same scene in millimetres or
// metres gets the same vertices, as K ∝ 1/s², H ∝ 1/s and σ ∝ 1/s; a noisy bake (marching
// cubes on a level set, sub-cell jitter) raises σ and so T above its noise, whatever c is.
//
// Then, in this order:
//   1. smoothing: Jacobi steps of the area-weighted one-ring mean of the field over the free
//      surface (curvature_smoothing.hpp), as many as spread it over a Gaussian of standard
//      deviation `smoothing_radius` edge lengths (one step spreads it by ℓ²/3 per axis on a
//      regular mesh: steps = 3 r²), which damps the vertex-to-vertex noise of the cotangent
//      curvature on marching-cubes meshes at the scale of the cells, on any resolution;
//   2. the tank's walls: the field is faded to 0 within a few edge lengths of the walls of a
//      closed volume (tank_walls.hpp), where the meniscus and the marching cubes' rounding
//      curve the water like a crest over a strip as wide as the droop;
//   3. over a sequence, blending with the previous frame (flow_coherence.hpp);
//   4. fading: a region (connected free-surface vertices with s >= 1, or s <= −1) whose area is
//      below A_min (a speck), whose peak |s| is barely 1, or that is not among the
//      `max_regions` most salient fades out: s is scaled down until its peak is below 1 (so it
//      is not drawn), and regions between A_min and 2 A_min, with a peak between 1 and 1.5, or
//      with a salience between the first one left out and twice it are scaled part way. The
//      salience of a region is Σ A (|s| − 1) over its vertices: how much and how strongly it
//      stands out. A region that is born starts at a point and grows, one that dies shrinks to
//      a point: nothing pops. A_min is in scene units², 0.002 L² by default; A_min = 0 turns
//      the fading off;
//   5. labels: +1 where s >= 1, −1 where s <= −1, else 0.
// The field written out (texture coordinates, CSV, PLY) is the one labels are taken from, so
// POV-Ray, interpolating s inside each triangle and cutting it at ±1 per pixel, draws smooth
// region boundaries that agree with the labels at the vertices.
//
// The shading normals (`shading_normal`) are the curvature normals smoothed the same way, over
// `shading_radius` and over every vertex whose curvature is defined, and on the up-facing part
// tilted back towards up by the walls' weight: the toon bands are chosen
// from them, so band edges follow the waves rather than the triangles, and the strip along a
// tank's walls shades as the calm water does. `normal_noise` is their noise floor (that of
// their horizontal components, noise_floor.hpp), which scenes put the band limits above.
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

// The criterion's defaults, every tolerance of the flow stage in one place.
struct FlowDefaults {
  double threshold_relative;   // c in T = c / L (mean) or c / L², L = sqrt(free-surface area)
  double smoothing_radius;     // Gaussian standard deviation of the field's smoothing, edge lengths
  double shading_radius;       // the same for the shading normals
  double min_region_relative;  // A_min / L²
  double noise_multiple;       // z in T >= z σ; 0: no noise floor
  double wall_near, wall_far;  // the walls' fade, edge lengths from a wall; 0, 0: none
  std::size_t max_regions;     // drawn regions at most; 0: no limit
};
FlowDefaults flow_defaults(FlowCriterion criterion);

// The Jacobi steps that smooth over a Gaussian of `radius_in_edge_lengths` (step 1 above).
int smoothing_steps_for_radius(double radius_in_edge_lengths);

// The free-surface selection's settings (free_surface.hpp, the up axis among them), then the
// flow field's.
struct FlowOptions : FreeSurfaceOptions {
  FlowCriterion criterion = FlowCriterion::mean;
  std::optional<double> threshold;           // absolute T; overrides threshold_relative
  std::optional<double> threshold_relative;  // c; default: flow_defaults(criterion)'s
  // Unset, these take the criterion's defaults (flow_defaults); for paper no smoothing, no
  // fading, no noise floor and no walls, so that it stays the paper's rule. An explicit
  // threshold (absolute or relative) is taken as it is, without the noise floor.
  std::optional<int> smoothing_steps;     // Jacobi steps over the free surface
  std::optional<double> min_region_area;  // absolute A_min (scene units²)
  // The shading normals and their noise floor, which only scenes use: `analyze` writes neither,
  // and their smoothing, of vectors, is most of the flow stage's time. Nothing else depends on
  // them.
  bool shading_normals = true;
};

enum FlowLabel : std::int8_t { valley = -1, none = 0, ridge = 1 };

// The label s gives a vertex before fading: ridge at s >= 1, valley at s <= −1, none between.
std::int8_t region_sign(double s);

struct FlowRegions {
  std::vector<double> field;  // per vertex: s (0 off the free surface); regions at |s| >= 1
  std::vector<double> smoothed_field;  // s after step 1, before coherence and fading
  std::vector<std::int8_t> label;      // per vertex: FlowLabel
  FlowCriterion criterion = FlowCriterion::mean;
  double threshold = 0.0;             // T actually used
  double scale_length = 0.0;          // L = sqrt(free-surface area)
  double min_region_area = 0.0;       // A_min actually used
  std::size_t max_regions = 0;        // the salience limit actually used; 0: none
  double noise_floor = 0.0;           // σ of this frame's smoothed field source (H, or sign(H)|K|)
  double sequence_noise_floor = 0.0;  // σ the threshold was held above (the sequence's)
  std::size_t walls = 0;              // tank walls found (tank_walls.hpp)
  std::vector<Vec3> shading_normal;   // per vertex: unit normal the toon bands are chosen from;
                                      // empty without FlowOptions::shading_normals
  double normal_noise = 0.0;          // noise floor of the shading normals' horizontal parts
  double median_edge_length = 0.0;
  double rest_height = 0.0;
  Box3 region_of_interest;                 // bounding box of the regions; empty when there are none
  std::vector<std::uint8_t> free_surface;  // per vertex: 1 on the free surface (free_surface.hpp)
  std::size_t free_surface_vertices = 0;
  std::size_t free_surface_patches_dropped = 0;
  std::size_t ridge_vertices = 0;
  std::size_t valley_vertices = 0;
  std::size_t regions = 0;       // drawn regions (connected, one sign)
  std::size_t specks_faded = 0;  // regions faded in part or whole
};

class FlowCoherence;

// With `coherence` (a sequence's state, flow_coherence.hpp), step 2 blends this frame's field
// with the frames it saw before.
FlowRegions find_flow_regions(const TriangleMesh& mesh, const MeshTopology& topology,
                              const CurvatureField& curvature, const FlowOptions& options,
                              FlowCoherence* coherence = nullptr);

// Steps 3 and 4 of the header on `field` (s before the fading, after coherence for example):
// fades the specks, then sets flow.field, the labels, the counts and the region of interest.
void label_flow_field(const TriangleMesh& mesh, std::span<const double> vertex_area,
                      std::vector<double> field, FlowRegions& flow);

}  // namespace toonwater
