// The edge between a closed liquid volume's free surface and its body (its walls and floor),
// cut inside the faces.
//
// A face is free surface when it points up (upward_faces, mesh2_writer.hpp). Drawn face by face,
// the edge follows the faces' edges; where a wave meets a wall of the tank, a marching-cubes
// mesh steps a cell at a time between wall and surface, and the edge was a row of teeth that
// changed from frame to frame. The edge is drawn instead along the iso-line 1/2 of
//   φ(v) = (the angles at v of its faces that point up) / (all its faces' angles at v),
// cut inside the faces (level_split.hpp): a smooth curve through the steps, and along a sharp
// straight edge between a wall and the water (φ = 1/2 on it) the edge itself. A face that the
// iso-line does not cross takes the side of its corners when it reaches across (its least
// height) no more than two median edge lengths, as a step of the mesh does, else its own: a
// large face, which the simplification made of many cells of one kind, stays what it is. So
// does the largest region of each kind (faces of that kind connected through their corners)
// where the iso-line would leave nothing of it: a box of twelve faces, whose top's corners are
// all the box's corners (φ = 1/3), is too coarse for the iso-line, and keeps its top as water.
#pragma once

#include "scene/prepared_surface.hpp"
#include "scene/scene_mesh.hpp"

#include <vector>

namespace toonwater {

// Per vertex: φ above, 0 for a vertex without faces; `upward` one per face.
std::vector<double> upward_angle_shares(const SceneMesh& mesh, const std::vector<bool>& upward);

// Cuts the surface and its coordinates `uv` (empty or one per vertex) along the edge above, in
// place; per face of the result: whether it is free surface.
std::vector<bool> cut_free_surface_from_body(PreparedSurface& surface,
                                             std::vector<TextureCoordinate>& uv);

}  // namespace toonwater
