#include "sim/height_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace toonwater::sim {

HeightField make_height_field(double x_min, double x_max, double z_min, double z_max, int cells) {
  if (cells < 2 || !(x_max > x_min) || !(z_max > z_min))
    throw std::invalid_argument("height field: needs at least 2 cells and a non-empty extent");
  const double longest = std::max(x_max - x_min, z_max - z_min);
  HeightField f;
  f.spacing = longest / cells;
  f.nx = static_cast<int>(std::lround((x_max - x_min) / f.spacing)) + 1;
  f.nz = static_cast<int>(std::lround((z_max - z_min) / f.spacing)) + 1;
  f.x0 = x_min;
  f.z0 = z_min;
  const auto n = static_cast<std::size_t>(f.nx) * static_cast<std::size_t>(f.nz);
  f.height.assign(n, 0.0);
  f.velocity.assign(n, 0.0);
  return f;
}

}  // namespace toonwater::sim
