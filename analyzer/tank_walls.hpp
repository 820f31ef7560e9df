// The walls of a tank: where a closed liquid volume lies against the sides of its domain.
//
// A simulation's liquid fills its (axis-aligned) domain up to the walls, and its mesh there is a
// flat vertical sheet on a side of the mesh's bounding box. Along it the free surface droops and
// curves into the wall over a few cells (the meniscus of the level set, and marching cubes
// rounding the corner): a strip that is as curved as a crest and tilted like a wave flank, yet
// is no flow an animator would draw. A side of the bounding box across the up axis is a wall
// when the mesh has vertices on it (within half an edge length) along at least half of its
// length, in stretches of one edge length: the liquid lies against a wall along the whole side,
// however shallow it is there, while a wave or a splash reaching the box's side touches it over
// a short stretch. Only a closed volume has walls: the border of an open sheet (an ocean tile)
// is a cut through waves that go on.
//
// The weight of a vertex is 0 within `near` of a wall (horizontal distance to the side's plane),
// 1 beyond `far`, and a smoothstep between: the flow field and the shading's tilt are multiplied
// by it, so the wall strip stays calm while a wave running beside a wall keeps its part farther
// out, and a region that reaches the strip fades into it rather than being cut.
#pragma once

#include "analyzer/mesh.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace toonwater {

struct TankWalls {
  // The four sides across the up axis: (low, high) of the first, then of the second horizontal
  // axis; true where the side is a wall.
  std::array<bool, 4> wall{};
  Box3 box;  // the mesh's bounding box
  std::size_t count() const {
    return static_cast<std::size_t>(wall[0] + wall[1] + wall[2] + wall[3]);
  }
};

// For a closed mesh; `edge_length`: its median edge length (edge_length.hpp).
TankWalls find_tank_walls(const TriangleMesh& mesh, Axis up, double edge_length);

// Per vertex, the weight above; all 1 without walls. `near` < `far`, both in scene units.
std::vector<double> wall_weights(const TriangleMesh& mesh, Axis up, const TankWalls& walls,
                                 double near, double far);

}  // namespace toonwater
