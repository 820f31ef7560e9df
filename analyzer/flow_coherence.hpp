// Temporal coherence of the water-flow regions over a frame sequence.
//
// Simulation meshes change topology every frame (marching cubes), so the field of one frame
// cannot simply be compared with the last one's vertex by vertex. Each frame's free-surface
// vertices find their closest free-surface vertex of the previous frame within `max_distance`
// edge lengths (point_grid.hpp), their predecessor, and carry the previous frame's values from
// the closest point of the faces around it, interpolated linearly there (closest_point.hpp):
// the previous surface's own field, sampled where the vertex lies. The predecessor's value alone
// would snap the field to the previous frame's vertices, and carried frame after frame, with a
// weight of b, it draws a region's edge as saw teeth a cell deep wherever the water moves. The
// flow field s (flow_regions.hpp) is blended with the carried one,
//   s̃ = (1 − b) s + b s̃_prev                      (exponential blend),
// with b = rise_blend where the field grows (s has s̃_prev's sign and a larger magnitude) and
// b = blend elsewhere, in the spirit of DeCarlo et al., "Interactive rendering of suggestive
// contours with temporal coherence" (NPAR 2004), who fade lines in and out by strength. A
// symmetric blend averages a crest that moves a cell or more a frame (the bow wave of a
// Mantaflow wake does) with the calm water it has left and loses it for frames; following growth
// faster keeps it, and the slower fading still damps the frame-to-frame noise.
//
// A region can also die by turning over: a crown's ring collapses and the crest becomes a
// trough. Blended with the other sign, it would vanish in one frame. Regions are therefore
// tracked: the parts this frame's blended field draws (|s̃| >= 1, one sign, connected) continue
// the regions of the frame before that they overlap with the same sign, through the vertices'
// predecessors. A region whose successors cover less than `successor_share` of its area dies;
// where its field turned over, its sign fades no faster than as if s had gone to 0:
//   s̃ = sign(s̃_prev) · min(b |s̃_prev|, C),   C = (b^−(k−1) + b^−k) / 2,
// wherever the blend keeps less, s̃_prev here the predecessor's own: the region fades where it
// was, and the water that turned over rose or fell there (a crest a cell high becomes a trough
// in one frame), which moves the closest point of the surface it left off the crest line. For k =
// turn_over_frames the cap takes it under the threshold of 1 in frame k + 1, and each frame before
// keeps the part where it was strongest: the ring shrinks and goes. A region that moves on (a crest
// running into the trough ahead of it) has its successors and is blended as it is, so it is not
// held back where it has left. The fading and labels are then taken from s̃ as for a single frame
// (label_flow_field).
//
// Everything stays continuous in time: s̃ moves by a fraction of its change each frame, so a
// region boundary (the iso-line s̃ = ±1 inside the triangles) slides and never jumps; a region
// that appears is hidden while its area is below A_min and then grows from its peak; one that
// dies shrinks the same way. No label is held for a number of frames and no second threshold
// holds a region once its field has gone: both froze regions that the water had left, and
// with a continuous field a value hovering at the threshold moves a boundary by a fraction of a
// triangle, not a label by a vertex.
//
// The shading normals that choose the toon bands (flow_regions.hpp) are carried and blended the
// same way where they change by no more than the noise, and normalised: ñ = (1 − b) n + b ñ_prev
// with b = normal_blend · max(0, 1 − (|n − ñ_prev| / (z σ))²), σ the frame's normal noise floor and
// z = normal_noise_multiple. A band edge on settling water then moves with the water rather
// than with the mesh's sub-cell noise, which each frame draws afresh (for b = 0.5 the noise's
// spread falls by sqrt((1 − b)/(1 + b)) = 0.58), while a wave that moves, turning the normals by
// more than the noise does, is taken as it is: a bow wave running into calm water is not
// averaged with the calm water it runs into.
//
// Flicker is measured as the share of free-surface area (mixed Voronoi areas) whose label
// differs from the one the previous frame drew where the vertex lies: the label of its drawn
// field, carried as above. The label of the closest vertex instead would favour the snapping
// the carrying avoids (a field copied from the closest vertex keeps that vertex's label,
// wherever the region's edge is drawn).
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/point_grid.hpp"
#include "analyzer/topology.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

struct CoherenceOptions {
  double blend = 0.8;  // weight of the carried-over (already blended) field: lag b/(1 − b) frames
  double rise_blend = 0.5;       // the same where the field grows (same sign, larger magnitude)
  int turn_over_frames = 2;      // a dying region whose field turns over fades for this many frames
  double successor_share = 0.5;  // a region whose successors cover less of its area dies
  double normal_blend = 0.5;  // the same for the shading normals, where they change by noise only
  double normal_noise_multiple = 3.0;  // z: a change of z noise floors is motion, not blended
  double max_distance = 2.0;  // in median edge lengths: farther vertices have no predecessor
};

// A frame's free surface as the next frame needs it.
struct FlowFrame {
  std::vector<Vec3> positions;
  std::vector<double> field;         // s̃: blended, before the specks are faded
  std::vector<double> drawn_field;   // s as drawn: after the fading, regions where |s| >= 1
  std::vector<Vec3> shading_normal;  // blended
  std::vector<Triangle> triangles;   // faces with every corner on the free surface
  VertexFaces vertex_faces;          // of `triangles`
  std::vector<std::int8_t> label;
  std::vector<std::int32_t> region;  // the drawn region (connected, one label); −1: none
  std::vector<double> region_area;   // per region
  double edge_length = 0.0;
};

class FlowCoherence {
 public:
  explicit FlowCoherence(CoherenceOptions options = {}) : options_(options) {}

  // The two halves, around label_flow_field (find_flow_regions calls them when given this):
  // blends `field`, this frame's s before fading, and `shading_normal` with the frames seen
  // before; then, once `flow` is labelled, remembers the frame and measures its flicker.
  void blend(const TriangleMesh& surface, std::span<const double> vertex_area,
             const FlowRegions& flow, std::vector<double>& field,
             std::vector<Vec3>& shading_normal);
  void remember(const TriangleMesh& surface, const CurvatureField& curvature,
                const FlowRegions& flow);

  // Both, for a frame labelled on its own: replaces flow.field, flow.label and the counts by
  // coherent ones. The first frame's are left as they are.
  void apply(const TriangleMesh& surface, const CurvatureField& curvature, FlowRegions& flow);

  // The noise floor the sequence's threshold is held above (flow_regions.hpp): the median of
  // the frames' own floors so far, this one's included (0 is no estimate and is left out). The
  // median changes by little from frame to frame, and a few violent frames do not move it.
  double sequence_noise_floor(double frame_noise_floor);

  // Flicker of the frame last remembered, against the frame before it: the share of
  // free-surface area whose label changed; 0 for the first frame.
  double last_flicker() const { return last_flicker_; }

 private:
  // The fading of the regions that die by turning over (the header), on the blended `field`.
  void hold_dying_regions(const TriangleMesh& surface, std::span<const double> vertex_area,
                          const FlowRegions& flow, std::vector<double>& field);

  CoherenceOptions options_;
  FlowFrame previous_, pending_;
  Box3 previous_bounds_, pending_bounds_;   // of the frames' positions, for the grid
  std::vector<std::int32_t> predecessor_;   // per vertex of the pending frame, −1: none
  std::vector<std::int8_t> carried_label_;  // per vertex: the label drawn there in the frame before
  std::vector<std::int32_t> surface_index_;  // per vertex: its place in pending_, −1: none
  std::vector<std::uint8_t> turned_over_;  // per vertex: s has the other sign than a drawn s̃_prev
  bool has_previous_ = false;
  std::vector<double> noise_floors_;
  double last_flicker_ = 0.0;
};

// Flicker between two labelled frames without coherence: the share of `current`'s free-surface
// area whose label differs from the one `previous` drew where its vertex lies (the header).
double label_flicker(const FlowFrame& previous, const TriangleMesh& surface,
                     const CurvatureField& curvature, const FlowRegions& flow);

// The free-surface part of a frame, unblended, as FlowCoherence and label_flicker take it.
FlowFrame flow_frame(const TriangleMesh& surface, const CurvatureField& curvature,
                     const FlowRegions& flow);

}  // namespace toonwater
