#include "sim/mesh_builders.hpp"

#include <cmath>
#include <numbers>

namespace toonwater::sim {
namespace {

std::int32_t id(std::size_t i) { return static_cast<std::int32_t>(i); }

// Latitude–longitude surface: the south pole (index 0), rings 1 … rings−1 at polar angles
// π·(1 − k/rings), the north pole last. `position(cos polar, azimuth)` places each vertex.
template <class Position>
TriangleMesh lat_long(int rings, int segments, Position position) {
  TriangleMesh m;
  m.positions.push_back(position(-1.0, 0.0));  // south pole: polar cosine −1
  for (int k = 1; k < rings; ++k) {
    const double polar = std::numbers::pi * (1.0 - static_cast<double>(k) / rings);
    for (int s = 0; s < segments; ++s)
      m.positions.push_back(position(std::cos(polar), 2.0 * std::numbers::pi * s / segments));
  }
  m.positions.push_back(position(1.0, 0.0));  // north pole
  const std::size_t north = m.positions.size() - 1;
  auto ring = [&](int k, int s) {
    return id(1 + static_cast<std::size_t>((k - 1) * segments + (s % segments)));
  };
  for (int s = 0; s < segments; ++s) {
    m.triangles.push_back({0, ring(1, s + 1), ring(1, s)});
    for (int k = 1; k + 1 < rings; ++k) {
      m.triangles.push_back({ring(k, s), ring(k, s + 1), ring(k + 1, s + 1)});
      m.triangles.push_back({ring(k, s), ring(k + 1, s + 1), ring(k + 1, s)});
    }
    m.triangles.push_back({id(north), ring(rings - 1, s), ring(rings - 1, s + 1)});
  }
  return m;
}

}  // namespace

TriangleMesh height_field_mesh(const HeightField& f) {
  TriangleMesh m;
  m.positions.reserve(f.height.size());
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i)
      m.positions.emplace_back(f.x(i), f.height[f.index(i, j)], f.z(j));
  m.triangles.reserve(2 * static_cast<std::size_t>(f.nx - 1) * static_cast<std::size_t>(f.nz - 1));
  for (int j = 0; j + 1 < f.nz; ++j)
    for (int i = 0; i + 1 < f.nx; ++i) {
      const auto a = id(f.index(i, j)), b = id(f.index(i + 1, j));
      const auto c = id(f.index(i + 1, j + 1)), d = id(f.index(i, j + 1));
      // Winding a→d→b is counter-clockwise seen from +y: (d − a) × (b − a) = z × x = +y.
      if ((i + j) % 2 == 0) {
        m.triangles.push_back({a, d, c});
        m.triangles.push_back({a, c, b});
      } else {
        m.triangles.push_back({a, d, b});
        m.triangles.push_back({b, d, c});
      }
    }
  return m;
}

TriangleMesh uv_sphere(const Vec3& centre, double radius, int rings, int segments) {
  return lat_long(rings, segments, [&](double cos_polar, double azimuth) {
    const double sin_polar = std::sqrt(std::max(0.0, 1.0 - cos_polar * cos_polar));
    return Vec3(centre + radius * Vec3(sin_polar * std::cos(azimuth), cos_polar,
                                       -sin_polar * std::sin(azimuth)));
  });
}

TriangleMesh capsule(const Vec3& a, const Vec3& b, double radius, int segments) {
  // A sphere split at its equator, the halves pushed apart to a and b: polar axis along b − a.
  const Vec3 axis = (b - a).normalized();
  const Vec3 helper = std::abs(axis.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = axis.cross(helper).normalized();
  const Vec3 w = u.cross(axis);  // (u, axis, w) right-handed, like (x, y, z) in uv_sphere
  // Odd: no ring on the equator; the band between the two rings nearest it is the cylinder.
  const int rings = 2 * ((segments + 3) / 4) + 1;
  return lat_long(rings, segments, [&](double cos_polar, double azimuth) {
    const double sin_polar = std::sqrt(std::max(0.0, 1.0 - cos_polar * cos_polar));
    const Vec3& end = cos_polar > 0 ? b : a;
    return Vec3(end + radius * (sin_polar * std::cos(azimuth) * u + cos_polar * axis -
                                sin_polar * std::sin(azimuth) * w));
  });
}

void append(TriangleMesh& mesh, const TriangleMesh& part) {
  const auto offset = id(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(), part.positions.begin(), part.positions.end());
  for (const Triangle& t : part.triangles)
    mesh.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
}

}  // namespace toonwater::sim
