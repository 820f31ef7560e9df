// Simplification of the water's render mesh for POV-Ray, whose parse time grows with the faces
// (about 1.4 µs a face, most of a big frame's parse; povray-notes.md). Calm water needs few
// triangles, so each frame's mesh is decimated by halfedge collapses on an OpenMesh TriMesh
// (vertices never move, so every kept vertex keeps its position, normal and fields):
//
//   order        passes over the vertices in index order; each collapses a vertex into the
//                neighbour of least quadric error (Garland & Heckbert, "Surface simplification
//                using quadric error metrics", SIGGRAPH 1997; shortest edge on ties) that every
//                constraint allows, and leaves the vertices around that collapse to the next
//                pass, which spreads a pass's collapses over the surface; only they are looked
//                at again. Passes run until one collapses nothing.
//   topology     the link condition and the tests of OpenMesh's is_collapse_ok and DecimaterT;
//   shape        no face turns by more than max_face_turn_degrees, no new sliver worse than
//                max_aspect_ratio (as ModNormalFlippingT and ModAspectRatioT);
//   geometry     the original surface stays within `tolerance` of the simplified one: each
//                face carries an estimate e_f of that distance which only grows, and a collapse
//                of v0 into v1 gives the faces it changes e = max e_f (star of v0) + d(p0, new
//                star), refused when e > tolerance (the tests measure the Hausdorff distance);
//   textures     the per-vertex texture coordinates u (L·n) and v (the flow field s) stay
//                within a bound: each vertex carries the range of the original values it
//                stands for, and a collapse is refused when the range over v0, v1 and v0's
//                neighbours exceeds the bound or straddles a level the template cuts at (band
//                thresholds, s = ±1), so bands and flow regions keep their exact boundaries;
//   boundary     a boundary vertex only collapses along a straight boundary, so the water's
//                outline keeps its shape.
//
// OpenMesh holds the connectivity and does the collapses; the tests run on flat arrays. (The
// library's DecimaterT evaluates every halfedge around each collapse again, some 40 checks a
// collapse, and took 19 times as long.) `tolerance` comes from a bound in pixels at the
// frame's camera (screen_tolerance). Frames with no faces, or that OpenMesh cannot hold
// (non-manifold), pass through unchanged.
#pragma once

#include "scene/prepared_surface.hpp"
#include "scene/scene_writer.hpp"

#include <cstddef>
#include <vector>

namespace toonwater {

struct SimplifyOptions {
  double tolerance = 0;          // world units; 0 leaves the mesh as it is
  std::vector<double> u_levels;  // iso-values of u that must not move
  std::vector<double> v_levels;  // iso-values of v that must not move
  double u_tolerance = 0;        // largest change of u
  double v_tolerance = 0;        // largest change of v
};

struct SimplifyStats {
  std::size_t faces_before = 0, faces_after = 0;
  bool simplified = false;  // false: passed through unchanged
};

// The options of the toon (or curvature-view) coordinates written for `water`, whose bands
// change at L·n = `band_thresholds` (scene_writer.hpp's water_thresholds), with a geometric
// `tolerance` in world units.
SimplifyOptions simplify_options(const WaterConfig& water,
                                 std::pair<double, double> band_thresholds, const FlowConfig* flow,
                                 double tolerance);

// The largest world distance that moves no point nearer than `nearest_distance` to the camera
// by more than `pixels` on a `width`×`height` image with a horizontal field of view of
// `angle_degrees`. For a pinhole camera a displacement δ at depth z moves a point by at most
// f·δ·sqrt(1 + tx² + ty²)/z pixels (f = width / (2 tan(angle/2)), |tx|, |ty| the half-field
// tangents), and z ≥ d·cos θ on screen, with tan² θ = tx² + ty²: δ = pixels·d·cos²θ / f.
double screen_tolerance(double pixels, double nearest_distance, double angle_degrees, int width,
                        int height);

// Simplifies the surface's mesh, its per-vertex data (flow field, view values) and its texture
// coordinates `uv` (texture_coordinates in frame_include.hpp) in place.
SimplifyStats simplify_surface(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                               const SimplifyOptions& options);

// A water frame simplified for the scene's camera: `water.simplify` pixels at the camera's
// reach of the frame, with the texture coordinates `uv` and band thresholds the frame is
// written with (`flow`: the frame's flow settings, if any).
SimplifyStats simplify_water(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                             const SceneLayout& layout, const FlowConfig* flow);

}  // namespace toonwater
