// How much water a sphere displaces, column by column: the source term of the wave solver.
//
// Over node (x, z) the sphere (centre c, radius r) spans heights c_y ± s with
// s = √(r² − ρ²), ρ the horizontal distance to the centre. The part below the rest level
// y = 0 has thickness  d = max(0, min(c_y + s, 0) − (c_y − s)),  the volume per unit area the
// sphere pushes aside there (linear theory: measured from the rest level, not the moving
// surface). Moving the sphere from c to c' changes the water by d(c') − d(c).
#pragma once

#include "sim/height_field.hpp"

#include <Eigen/Core>

#include <vector>

namespace toonwater::sim {

// Submerged thickness per node of a sphere at `centre` (x, y, z; y up).
std::vector<double> sphere_displacement(const HeightField& field, const Eigen::Vector3d& centre,
                                        double radius);

}  // namespace toonwater::sim
