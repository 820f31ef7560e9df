// Affine maps of mesh positions, x ↦ A·x + b, for meshes whose coordinates are not world
// coordinates — Mantaflow's caches store the liquid in normalised domain space
// (docs/inputs.md). A map with det A < 0 mirrors the mesh; it reverses every
// triangle's winding as well, so that normals still point to the side they pointed to before.
#pragma once

#include "analyzer/mesh.hpp"

#include <Eigen/Core>

#include <filesystem>
#include <span>

namespace toonwater {

struct AffineTransform {
  Eigen::Matrix3d linear = Eigen::Matrix3d::Identity();  // A
  Vec3 translation = Vec3::Zero();                       // b
};

// The map from its 3×4 matrix [A | b] given row by row: a00 a01 a02 b0, a10 a11 a12 b1, a20 ...
// Throws std::invalid_argument if an entry is NaN or infinite or A is singular (see below).
AffineTransform affine_from_rows(std::span<const double, 12> rows);

// x ↦ scale·x + translation. Throws std::invalid_argument as affine_from_rows does.
AffineTransform scale_then_translate(double scale, const Vec3& translation);

// Maps every position; reverses every triangle when the map mirrors (det A < 0). Throws
// InputError naming `source` (the mesh's file) and the vertex where a position overflows.
void apply_transform(const AffineTransform& transform, TriangleMesh& mesh,
                     const std::filesystem::path& source);

}  // namespace toonwater
