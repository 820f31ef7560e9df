#include "sim/body_displacement.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater::sim {

std::vector<double> sphere_displacement(const HeightField& f, const Eigen::Vector3d& centre,
                                        double radius) {
  std::vector<double> d(f.height.size(), 0.0);
  if (centre.y() - radius >= 0.0) return d;  // entirely above the water
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const double dx = f.x(i) - centre.x(), dz = f.z(j) - centre.z();
      const double rho2 = dx * dx + dz * dz;
      if (rho2 >= radius * radius) continue;
      const double s = std::sqrt(radius * radius - rho2);
      d[f.index(i, j)] = std::max(0.0, std::min(centre.y() + s, 0.0) - (centre.y() - s));
    }
  return d;
}

}  // namespace toonwater::sim
