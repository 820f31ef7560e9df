// Discrete curvature of a triangle mesh per vertex, after Meyer, Desbrun, Schröder and Barr,
// "Discrete Differential-Geometry Operators for Triangulated 2-Manifolds" (VisMath 2002).
//
//   A  = mixed Voronoi area (Voronoi part for non-obtuse triangles, area/2 at an obtuse corner,
//        area/4 at the other corners of an obtuse triangle)
//   K  = (2π − Σθ) / A                                   (angle deficit)
//   L  = Σ (cot α + cot β)(xᵢ − xⱼ)                     (cotangent Laplace–Beltrami of x)
//   H  = ±‖L‖/(4A), the sign of L·n̂                     (Meyer et al. §5.1: half the length of
//        the mean curvature normal; H > 0 on a sphere with outward normals); where L leans
//        more than 10° from n̂, (L·n̂)/(4A cos 10°) instead, so H stays continuous
//   k1,2 = H ± sqrt(max(H² − K, 0))
//   n̂  = angle-weighted vertex normal (Thürmer and Wüthrich 1998)
//
// One pass over the faces on every core computes each face's terms once, over the flat position
// and triangle arrays (no halfedge circulators), and adds them to its corners' sums; a vertex
// whose faces span two cores' ranges is summed afterwards from its row, in the same order, so
// the result does not depend on the core count. See curvature.cpp for how the angle sum is kept
// exact, how thin and degenerate faces are handled (L from the intrinsic Delaunay triangulation
// of mollified edge lengths where the mesh has caps or near-collinear faces), and boundaries
// and non-manifold vertices.
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace toonwater {

enum class CurvatureStatus : std::uint8_t {
  computed,      // from the vertex's own one-ring
  extrapolated,  // boundary, non-manifold or degenerate-face corner: mean of computed neighbours
  undefined,     // no area and no computed neighbour: all values 0
};

struct CurvatureField {
  std::vector<Vec3> normal;  // unit length; zero only where undefined
  std::vector<double> area;  // mixed Voronoi area
  std::vector<double> gaussian;
  std::vector<double> mean;  // k1 and k2 follow from K and H: principal_curvatures
  std::vector<CurvatureStatus> status;
  // Faces left out: a repeated corner or a zero-length edge (no shape).
  std::size_t degenerate_faces = 0;
  // Faces within ε of violating the triangle inequality (caps near 180°, collinear faces): if
  // there are any, every edge length is mollified by `mollification` (input units, else 0).
  std::size_t mollified_faces = 0;
  double mollification = 0.0;
  // Faces with an angle above 150°. If there are any, or mollified faces, the Laplacian's
  // cotangents come from the intrinsic Delaunay triangulation, made with this many flips.
  std::size_t cap_faces = 0;
  std::size_t intrinsic_flips = 0;
  std::size_t extrapolated_vertices = 0;
  std::size_t undefined_vertices = 0;
};

// `mesh` should be consistently oriented (orient_consistently) for the signs to mean anything.
CurvatureField compute_curvature(const TriangleMesh& mesh, const MeshTopology& topology);

struct PrincipalCurvatures {
  double k1 = 0.0, k2 = 0.0;  // k1 >= k2
};

// k1,2 = H ± sqrt(max(H² − K, 0)); computed where they are needed rather than stored beside K
// and H (two arrays of the field's size).
inline PrincipalCurvatures principal_curvatures(double gaussian, double mean) {
  const double root = std::sqrt(std::max(mean * mean - gaussian, 0.0));
  return {mean + root, mean - root};
}

// Shared by the estimators.
// Sets K and H of vertex v.
void set_curvature(CurvatureField& field, std::size_t v, double gaussian, double mean);
// Vertices whose status is `extrapolated` take the mean K and H of their `computed` neighbours;
// those with none become `undefined` (all zero). Then counts both kinds in the field.
void extrapolate_from_neighbours(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                 CurvatureField& field);

}  // namespace toonwater
