// A water surface sampled on a regular grid: the state of the examples' wave simulation.
//
// Y is up (the project's default): node (i, j) sits at x = x0 + i·spacing, z = z0 + j·spacing,
// at height `height[i + j·nx]` above the rest level y = 0.
#pragma once

#include <cstddef>
#include <vector>

namespace toonwater::sim {

struct HeightField {
  int nx = 0, nz = 0;            // nodes along x and z
  double x0 = 0, z0 = 0;         // position of node (0, 0)
  double spacing = 1;            // distance between neighbouring nodes
  std::vector<double> height;    // surface elevation above the rest level
  std::vector<double> velocity;  // ∂height/∂t

  std::size_t index(int i, int j) const { return static_cast<std::size_t>(i + j * nx); }
  double x(int i) const { return x0 + i * spacing; }
  double z(int j) const { return z0 + j * spacing; }
};

// A field at rest covering [x_min, x_max] × [z_min, z_max], with `cells` cells along the longer
// side (the shorter side gets the number that keeps the cells square).
HeightField make_height_field(double x_min, double x_max, double z_min, double z_max, int cells);

}  // namespace toonwater::sim
