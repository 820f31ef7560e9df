// Triangle meshes for the examples: the water surface of a height field, and the simple solids
// the scenes put in it (spheres, capsules). Y is up; every mesh is outward (or, for the open
// water sheet, upward) oriented, counter-clockwise seen from outside.
#pragma once

#include "analyzer/mesh.hpp"
#include "sim/height_field.hpp"

namespace toonwater::sim {

// The surface y = height as an open sheet, one vertex per node. Each grid cell is split along
// alternating diagonals (a "union jack" pattern), so the mesh has no preferred direction and
// circular ripples stay circular in the curvature.
TriangleMesh height_field_mesh(const HeightField& field);

// A UV sphere: `rings` latitude bands, `segments` longitude segments, one vertex per pole.
TriangleMesh uv_sphere(const Vec3& centre, double radius, int rings, int segments);

// A closed cylinder with hemispherical caps between `a` and `b`.
TriangleMesh capsule(const Vec3& a, const Vec3& b, double radius, int segments);

// Appends `part` to `mesh` (indices shifted).
void append(TriangleMesh& mesh, const TriangleMesh& part);

}  // namespace toonwater::sim
