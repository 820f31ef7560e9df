// Water-like test meshes: open height fields and closed tanks with a height field on top.
#pragma once

#include "corpus/analytic_surfaces.hpp"

#include <cmath>
#include <functional>
#include <vector>

namespace toonwater::test {

using HeightFunction = std::function<double(double, double)>;

// Open height field z = f(x, y) over [−1, 1]², n×n vertices, counter-clockwise from +z.
inline TriangleMesh height_field(int n, const HeightFunction& f) {
  TriangleMesh m = make_saddle(n, 1.0).mesh;
  for (Vec3& p : m.positions) p.z() = f(p.x(), p.y());
  return m;
}

// A closed "tank": the height field on top, vertical walls down to z = −1 and a floor.
inline TriangleMesh tank(int n, const HeightFunction& f) {
  TriangleMesh m = height_field(n, f);
  const auto top = static_cast<std::int32_t>(m.positions.size());
  const std::size_t top_faces = m.triangles.size();
  for (std::int32_t v = 0; v < top; ++v)
    m.positions.emplace_back(m.positions[v].x(), m.positions[v].y(), -1.0);
  for (std::size_t face = 0; face < top_faces; ++face) {  // floor: the top's faces, reversed
    const Triangle t = m.triangles[face];
    m.triangles.push_back({t[0] + top, t[2] + top, t[1] + top});
  }
  // Border ring of the grid, counter-clockwise seen from +z (index = i·n + j, x along i).
  std::vector<std::int32_t> ring;
  for (int i = 0; i < n - 1; ++i) ring.push_back(i * n);            // y = −1, x rising
  for (int j = 0; j < n - 1; ++j) ring.push_back((n - 1) * n + j);  // x = +1, y rising
  for (int i = n - 1; i > 0; --i) ring.push_back(i * n + n - 1);    // y = +1, x falling
  for (int j = n - 1; j > 0; --j) ring.push_back(j);                // x = −1, y falling
  for (std::size_t r = 0; r < ring.size(); ++r) {
    const std::int32_t a = ring[r], b = ring[(r + 1) % ring.size()];
    m.triangles.push_back({a, a + top, b + top});  // outward: the ring runs counter-clockwise
    m.triangles.push_back({a, b + top, b});
  }
  return m;
}

inline HeightFunction bump(double amplitude, double x0, double y0, double width) {
  return [=](double x, double y) {
    return amplitude * std::exp(-((x - x0) * (x - x0) + (y - y0) * (y - y0)) / (width * width));
  };
}

}  // namespace toonwater::test
