// A surface cut along an iso-line of a per-vertex field, so that a per-face choice follows it.
//
// A choice made per face (which texture a face takes) draws its edge along the faces' edges: on
// a marching-cubes mesh, a staircase a cell deep that changes from frame to frame. Cut where the
// field, interpolated linearly inside each face, crosses `level` (marching triangles, the
// two-dimensional case of Lorensen and Cline, "Marching cubes", SIGGRAPH 1987), the edge lies on
// the iso-line instead, which is as smooth as the field: a face whose corners lie on both sides
// becomes a triangle on one side and two on the other, the edge's point at
//   p = a + t·(b − a),  t = (level − f(a)) / (f(b) − f(a)),
// and every per-vertex value (position, normal, texture coordinates, flow field, view values)
// interpolated there alike. Each cut edge gets one point, shared by both its faces, so the
// surface keeps its connectivity and stays closed. A point within level_split_margin of the
// edge's length from an end is that end (the pieces it would leave empty are dropped), so that
// no piece is a sliver: the iso-line moves by at most that share of an edge, and one through a
// vertex (a corner at the level) goes along the faces' edges.
#pragma once

#include "scene/prepared_surface.hpp"
#include "scene/scene_mesh.hpp"

#include <span>
#include <vector>

namespace toonwater {

constexpr double level_split_margin = 0.02;

// Cuts `surface` (its mesh and per-vertex data) and `uv` (empty or one per vertex) in place;
// `field` one per vertex, finite. Per face of the result: whether it lies above the level (its
// corners' field > level), or for a face left whole, when `uncut_side` holds one per face of
// the surface, the face's side there.
std::vector<bool> split_at_level(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                                 std::span<const double> field, double level,
                                 const std::vector<bool>& uncut_side = {});

}  // namespace toonwater
