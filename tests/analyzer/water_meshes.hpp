// Water-like test meshes: open height fields, closed tanks with a height field on top, a box.
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

// A box of water of twelve faces, y up: x and z in [−1, 1], y in [−0.4, 0], wound outward.
inline TriangleMesh water_box() {
  TriangleMesh box;
  for (int i = 0; i < 8; ++i)
    box.positions.emplace_back(i & 1 ? 1.0 : -1.0, i & 2 ? 0.0 : -0.4, i & 4 ? 1.0 : -1.0);
  // Outward-wound quads as two triangles each: -x, +x, -y, +y, -z, +z.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    box.triangles.push_back({q[0], q[1], q[2]});
    box.triangles.push_back({q[0], q[2], q[3]});
  }
  return box;
}

inline HeightFunction bump(double amplitude, double x0, double y0, double width) {
  return [=](double x, double y) {
    return amplitude * std::exp(-((x - x0) * (x - x0) + (y - y0) * (y - y0)) / (width * width));
  };
}

}  // namespace toonwater::test
