// Plain mesh data shared by every stage: flat arrays of positions and triangles.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

namespace toonwater {

using Vec3 = Eigen::Vector3d;
using Triangle = std::array<std::int32_t, 3>;

struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Triangle> triangles;
};

// The input's up axis; POV-Ray and the analyzer's "height" use it.
enum class Axis : std::uint8_t { x = 0, y = 1, z = 2 };

// An axis-aligned box, min and max corner included.
struct Box3 {
  Vec3 min = Vec3::Constant(0.0);
  Vec3 max = Vec3::Constant(-1.0);  // empty by default
  bool empty() const { return (max.array() < min.array()).any(); }
  bool contains(const Vec3& p) const {
    return (p.array() >= min.array()).all() && (p.array() <= max.array()).all();
  }
  // The box of no points: empty, and replaced by the first point or box added to it.
  static Box3 of_no_points() {
    return {Vec3::Constant(std::numeric_limits<double>::infinity()),
            Vec3::Constant(-std::numeric_limits<double>::infinity())};
  }
  // Grows the box to hold p, or another box.
  void add(const Vec3& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  void add(const Box3& box) {
    min = min.cwiseMin(box.min);
    max = max.cwiseMax(box.max);
  }
};

}  // namespace toonwater
