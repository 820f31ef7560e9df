// Intrinsic Delaunay triangulation of a triangle mesh: Fisher, Springborn, Bobenko and Schröder,
// "An Algorithm for the Construction of Intrinsic Delaunay Triangulations with Applications to
// Digital Geometry Processing" (SIGGRAPH 2006 course / Computing 2007), on intrinsic mollified
// edge lengths (Sharp and Crane, "A Laplacian for Nonmanifold Triangle Meshes", SGP 2020).
//
// The triangulation keeps the vertices and the intrinsic metric (edge lengths) of the surface
// and changes only its edges: an interior edge is flipped while the angles opposite it sum to
// more than π (cot α + cot β < 0), replacing it by the other diagonal of its two faces
// unfolded into the plane:
//   d² = ℓ_jk² + ℓ_jl² − 2 ℓ_jk ℓ_jl cos(θ_j¹ + θ_j²)
// Angles at vertices, and so Gaussian curvature, do not change; the cotangent Laplacian built
// on the result has non-negative weights and does not depend on how thin the input faces are.
// Boundary and non-manifold edges are never flipped. Before flipping, every length is
// increased by the same δ (the mollification): a face that violates the triangle inequality
// up to round-off becomes a thin but valid triangle.
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <array>
#include <cstddef>
#include <vector>

namespace toonwater {

struct IntrinsicTriangulation {
  std::vector<Triangle> faces;
  // lengths[f][c]: the edge from faces[f][c] to faces[f][(c + 1) % 3]
  std::vector<std::array<double, 3>> lengths;
  VertexFaces vertex_faces;  // over `faces`
  std::size_t flips = 0;
};

// Faces with a repeated corner or a zero-length edge are left out. Lengths are those of the
// positions times `scale`, plus `delta`. `vertex_faces` are the mesh's.
IntrinsicTriangulation intrinsic_delaunay(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                          double scale, double delta);

// Twice the area of a triangle with edge lengths a, b, c (Kahan, "Miscalculating Area and
// Angles of a Needle-like Triangle", 2014): accurate for needles and caps.
double double_area_from_lengths(double a, double b, double c);

}  // namespace toonwater
