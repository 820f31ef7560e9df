// Angle-weighted vertex normals (Thürmer and Wüthrich 1998): n_v = normalize(Σ θ_f · n_f) over
// the faces f around v, θ_f the face's corner angle at v. Used when no curvature is computed
// (flow regions off, objects); the analyzer computes the same normals alongside curvature.
// Degenerate faces contribute nothing; a vertex with no usable face gets a zero normal, which
// the mesh2 writer replaces.
#pragma once

#include "analyzer/mesh.hpp"

#include <vector>

namespace toonwater::povgen {

std::vector<Vec3> angle_weighted_normals(const TriangleMesh& mesh);

}  // namespace toonwater::povgen
