// Analytic test surfaces. Curvature formulas (outward or upward normals, H > 0 where the
// surface bends away from its normal, e.g. a sphere):
//   sphere     K = 1/R², H = 1/R
//   torus      K = cos v / (r (R + r cos v)),  H = (R + 2r cos v) / (2r (R + r cos v))
//   ellipsoid  h = sqrt(x²/a⁴ + y²/b⁴ + z²/c⁴),  K = 1/(a²b²c² h⁴),
//              H = (a² + b² + c² − x² − y² − z²) / (2 a²b²c² h³)
//   cylinder   K = 0, H = 1/(2r)
//   graph z = f(x, y), upward normal, W = sqrt(1 + fx² + fy²):
//              K = (fxx fyy − fxy²) / W⁴,
//              H = −((1 + fy²) fxx − 2 fx fy fxy + (1 + fx²) fyy) / (2 W³)
#include "corpus/analytic_surfaces.hpp"

#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <utility>

namespace toonwater {
namespace {

constexpr double pi = std::numbers::pi;

class JitterSource {
 public:
  explicit JitterSource(Jitter j) : fraction_(j.fraction), engine_(j.seed) {}
  // A random offset in [−fraction, fraction] · step.
  double offset(double step) {
    if (fraction_ == 0.0) return 0.0;
    return std::uniform_real_distribution<double>(-fraction_, fraction_)(engine_) * step;
  }

 private:
  double fraction_;
  std::mt19937 engine_;
};

std::int32_t index(int i, int j, int columns) { return i * columns + j; }

// Triangles of a grid of rows × columns vertices, counter-clockwise in (i, j) when i runs along
// the first parameter and j along the second. Columns wrap when `wrap_columns`, rows when
// `wrap_rows`.
void grid_triangles(int rows, int columns, bool wrap_rows, bool wrap_columns,
                    std::vector<Triangle>& triangles) {
  const int row_cells = wrap_rows ? rows : rows - 1;
  const int column_cells = wrap_columns ? columns : columns - 1;
  for (int i = 0; i < row_cells; ++i) {
    for (int j = 0; j < column_cells; ++j) {
      const int i1 = (i + 1) % rows, j1 = (j + 1) % columns;
      const std::int32_t a = index(i, j, columns), b = index(i1, j, columns),
                         c = index(i1, j1, columns), d = index(i, j1, columns);
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  }
}

struct GraphDerivatives {
  double f, fx, fy, fxx, fyy, fxy;
};

template <class Function>
AnalyticSurface make_graph(int n, double half_extent, Jitter jitter, Function f) {
  AnalyticSurface s;
  JitterSource rng(jitter);
  const double step = 2.0 * half_extent / (n - 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      double x = -half_extent + i * step, y = -half_extent + j * step;
      const bool border = i == 0 || j == 0 || i == n - 1 || j == n - 1;
      if (!border) {
        x += rng.offset(step);
        y += rng.offset(step);
      }
      const GraphDerivatives d = f(x, y);
      const double w2 = 1.0 + d.fx * d.fx + d.fy * d.fy;
      s.mesh.positions.emplace_back(x, y, d.f);
      s.gaussian.push_back((d.fxx * d.fyy - d.fxy * d.fxy) / (w2 * w2));
      s.mean.push_back(
          -((1.0 + d.fy * d.fy) * d.fxx - 2.0 * d.fx * d.fy * d.fxy + (1.0 + d.fx * d.fx) * d.fyy) /
          (2.0 * w2 * std::sqrt(w2)));
      s.interior.push_back(i >= 2 && j >= 2 && i < n - 2 && j < n - 2);
    }
  }
  // i runs along x, j along y: (i, j) → (i+1, j) → (i+1, j+1) is counter-clockwise from +z.
  grid_triangles(n, n, false, false, s.mesh.triangles);
  return s;
}

// Icosahedron subdivided `subdivisions` times, every vertex on the unit sphere.
TriangleMesh unit_icosphere(int subdivisions, Jitter jitter) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh m;
  for (const Vec3& p : {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                        Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                        Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)})
    m.positions.push_back(p.normalized());
  m.triangles = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int level = 0; level < subdivisions; ++level) {
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> midpoints;
    auto midpoint = [&](std::int32_t a, std::int32_t b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] =
          midpoints.try_emplace(key, static_cast<std::int32_t>(m.positions.size()));
      if (inserted) m.positions.push_back((m.positions[a] + m.positions[b]).normalized());
      return it->second;
    };
    std::vector<Triangle> finer;
    finer.reserve(4 * m.triangles.size());
    for (const Triangle& f : m.triangles) {
      const std::int32_t ab = midpoint(f[0], f[1]), bc = midpoint(f[1], f[2]),
                         ca = midpoint(f[2], f[0]);
      finer.push_back({f[0], ab, ca});
      finer.push_back({f[1], bc, ab});
      finer.push_back({f[2], ca, bc});
      finer.push_back({ab, bc, ca});
    }
    m.triangles = std::move(finer);
  }
  if (jitter.fraction > 0.0) {
    JitterSource rng(jitter);
    const double edge = 1.1 / std::ldexp(1.0, subdivisions);  // icosahedron edge ≈ 1.05
    for (Vec3& p : m.positions) {
      const Vec3 offset(rng.offset(edge), rng.offset(edge), rng.offset(edge));
      p = (p + offset - offset.dot(p) * p).normalized();
    }
  }
  return m;
}

}  // namespace

AnalyticSurface make_icosphere(int subdivisions, double radius, Jitter jitter) {
  AnalyticSurface s;
  s.mesh = unit_icosphere(subdivisions, jitter);
  for (Vec3& p : s.mesh.positions) p *= radius;
  const std::size_t n = s.mesh.positions.size();
  s.gaussian.assign(n, 1.0 / (radius * radius));
  s.mean.assign(n, 1.0 / radius);
  s.interior.assign(n, true);
  return s;
}

AnalyticSurface make_uv_sphere(int rings, int segments, double radius, Jitter jitter) {
  AnalyticSurface s;
  JitterSource rng(jitter);
  const double dtheta = pi / rings, dphi = 2.0 * pi / segments;
  // Latitudes 1 .. rings−1 as a grid, then the two poles.
  for (int i = 1; i < rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const double theta = i * dtheta + rng.offset(dtheta), phi = j * dphi + rng.offset(dphi);
      s.mesh.positions.push_back(radius * Vec3(std::sin(theta) * std::cos(phi),
                                               std::sin(theta) * std::sin(phi), std::cos(theta)));
      s.interior.push_back(true);
    }
  }
  // Rows run from the north pole down (θ grows), columns eastward: counter-clockwise outside.
  grid_triangles(rings - 1, segments, false, true, s.mesh.triangles);
  const auto north = static_cast<std::int32_t>(s.mesh.positions.size());
  s.mesh.positions.emplace_back(0, 0, radius);
  s.mesh.positions.emplace_back(0, 0, -radius);
  s.interior.push_back(true);
  s.interior.push_back(true);
  const std::int32_t south = north + 1, last_row = (rings - 2) * segments;
  for (int j = 0; j < segments; ++j) {
    const int j1 = (j + 1) % segments;
    s.mesh.triangles.push_back({north, j, j1});
    s.mesh.triangles.push_back({south, last_row + j1, last_row + j});
  }
  const std::size_t n = s.mesh.positions.size();
  s.gaussian.assign(n, 1.0 / (radius * radius));
  s.mean.assign(n, 1.0 / radius);
  return s;
}

AnalyticSurface make_torus(int major_segments, int minor_segments, double R, double r,
                           Jitter jitter) {
  AnalyticSurface s;
  JitterSource rng(jitter);
  const double du = 2.0 * pi / major_segments, dv = 2.0 * pi / minor_segments;
  for (int i = 0; i < major_segments; ++i) {
    for (int j = 0; j < minor_segments; ++j) {
      const double u = i * du + rng.offset(du), v = j * dv + rng.offset(dv);
      const double ring = R + r * std::cos(v);
      s.mesh.positions.emplace_back(ring * std::cos(u), ring * std::sin(u), r * std::sin(v));
      s.gaussian.push_back(std::cos(v) / (r * ring));
      s.mean.push_back((R + 2.0 * r * std::cos(v)) / (2.0 * r * ring));
      s.interior.push_back(true);
    }
  }
  grid_triangles(major_segments, minor_segments, true, true, s.mesh.triangles);
  return s;
}

AnalyticSurface make_ellipsoid(int subdivisions, double a, double b, double c, Jitter jitter) {
  AnalyticSurface s;
  s.mesh = unit_icosphere(subdivisions, jitter);
  const double abc2 = a * a * b * b * c * c;
  for (Vec3& p : s.mesh.positions) {
    p = Vec3(a * p.x(), b * p.y(), c * p.z());
    const double h = std::sqrt(p.x() * p.x() / (a * a * a * a) + p.y() * p.y() / (b * b * b * b) +
                               p.z() * p.z() / (c * c * c * c));
    s.gaussian.push_back(1.0 / (abc2 * h * h * h * h));
    s.mean.push_back((a * a + b * b + c * c - p.squaredNorm()) / (2.0 * abc2 * h * h * h));
    s.interior.push_back(true);
  }
  return s;
}

AnalyticSurface make_cylinder(int segments, int rings, double radius, double height,
                              Jitter jitter) {
  AnalyticSurface s;
  JitterSource rng(jitter);
  const double dphi = 2.0 * pi / segments, dz = height / rings;
  for (int i = 0; i <= rings; ++i) {
    for (int j = 0; j < segments; ++j) {
      const bool rim = i == 0 || i == rings;
      const double z = -0.5 * height + i * dz + (rim ? 0.0 : rng.offset(dz));
      const double phi = j * dphi + rng.offset(dphi);
      s.mesh.positions.emplace_back(radius * std::cos(phi), radius * std::sin(phi), z);
      s.interior.push_back(i >= 2 && i <= rings - 2);
    }
  }
  // Rows climb in z, columns run counter-clockwise around z: (i, j) → (i, j+1) → (i+1, j+1)
  // faces outward, which is the reverse of grid_triangles' order.
  grid_triangles(rings + 1, segments, false, true, s.mesh.triangles);
  for (Triangle& t : s.mesh.triangles) std::swap(t[1], t[2]);
  const std::size_t n = s.mesh.positions.size();
  s.gaussian.assign(n, 0.0);
  s.mean.assign(n, 0.5 / radius);
  return s;
}

AnalyticSurface make_saddle(int n, double half_extent, Jitter jitter) {
  return make_graph(n, half_extent, jitter, [](double x, double y) {
    return GraphDerivatives{(x * x - y * y) / 2.0, x, -y, 1.0, -1.0, 0.0};
  });
}

AnalyticSurface make_wave_field(int n, double amplitude, double wave_number, double half_extent,
                                Jitter jitter) {
  const double A = amplitude, k = wave_number;
  return make_graph(n, half_extent, jitter, [A, k](double x, double y) {
    const double sx = std::sin(k * x), cx = std::cos(k * x), sy = std::sin(k * y),
                 cy = std::cos(k * y);
    return GraphDerivatives{A * sx * cy,          A * k * cx * cy,      -A * k * sx * sy,
                            -A * k * k * sx * cy, -A * k * k * sx * cy, -A * k * k * cx * sy};
  });
}

}  // namespace toonwater
