// Tank walls; the rule is stated in tank_walls.hpp.
#include "analyzer/tank_walls.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace toonwater {

namespace {

// The two horizontal axes of `up`, in index order.
std::array<int, 2> horizontal_axes(Axis up) {
  const int u = static_cast<int>(up);
  return {u == 0 ? 1 : 0, u == 2 ? 1 : 2};
}

}  // namespace

TankWalls find_tank_walls(const TriangleMesh& mesh, Axis up, double edge_length) {
  TankWalls walls;
  walls.box = Box3::of_no_points();
  for (const Vec3& p : mesh.positions) walls.box.add(p);
  if (mesh.positions.empty() || !(edge_length > 0.0)) return walls;
  const auto axes = horizontal_axes(up);
  const double tolerance = 0.5 * edge_length;
  // Per side, which stretches of one edge length along it hold a vertex lying on it.
  std::array<std::vector<std::uint8_t>, 4> covered;
  for (int side = 0; side < 4; ++side) {
    const int along = axes[1 - side / 2];
    const double length = walls.box.max[along] - walls.box.min[along];
    covered[side].assign(
        static_cast<std::size_t>(std::clamp(std::ceil(length / edge_length), 1.0, 1e7)), 0);
  }
  for (const Vec3& p : mesh.positions) {
    for (int side = 0; side < 4; ++side) {
      const int axis = axes[side / 2], along = axes[1 - side / 2];
      const double plane = side % 2 ? walls.box.max[axis] : walls.box.min[axis];
      if (std::abs(p[axis] - plane) > tolerance) continue;
      const double at = (p[along] - walls.box.min[along]) / edge_length;
      const auto bin = static_cast<std::size_t>(
          std::clamp(at, 0.0, static_cast<double>(covered[side].size() - 1)));
      covered[side][bin] = 1;
    }
  }
  for (int side = 0; side < 4; ++side) {
    const auto count = std::count(covered[side].begin(), covered[side].end(), std::uint8_t{1});
    walls.wall[side] = 2 * static_cast<std::size_t>(count) >= covered[side].size();
  }
  return walls;
}

std::vector<double> wall_weights(const TriangleMesh& mesh, Axis up, const TankWalls& walls,
                                 double near, double far) {
  std::vector<double> weight(mesh.positions.size(), 1.0);
  if (walls.count() == 0 || !(far > near)) return weight;
  const auto axes = horizontal_axes(up);
  for (std::size_t v = 0; v < weight.size(); ++v) {
    const Vec3& p = mesh.positions[v];
    double distance = std::numeric_limits<double>::infinity();
    for (int side = 0; side < 4; ++side) {
      if (!walls.wall[side]) continue;
      const int axis = axes[side / 2];
      distance = std::min(distance,
                          side % 2 ? walls.box.max[axis] - p[axis] : p[axis] - walls.box.min[axis]);
    }
    const double x = std::clamp((distance - near) / (far - near), 0.0, 1.0);
    weight[v] = x * x * (3.0 - 2.0 * x);
  }
  return weight;
}

}  // namespace toonwater
