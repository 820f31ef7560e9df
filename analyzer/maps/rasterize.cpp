// Top-down rasteriser (see top_down_map.hpp). Two passes over flat arrays:
//  1. coverage: each upward-facing triangle, projected on the map plane, visits the pixel
//     centres inside it (edge functions, inclusive so shared edges leave no cracks) and keeps
//     the face and barycentric weights of the highest point seen so far (a depth test on the
//     interpolated height: the topmost layer wins);
//  2. resolve (split over the cores): every covered pixel interpolates its face's corner
//     values with those weights, once, however much overdraw there was. Labels are categorical, so
//     a pixel takes the label of its nearest corner (largest weight) instead of a blend.
#include "analyzer/maps/top_down_map.hpp"

#include "common/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace toonwater {

Vec3 map_u_axis(Axis up) { return up == Axis::x ? Vec3::UnitY() : Vec3::UnitX(); }

Vec3 map_v_axis(Axis up) {
  switch (up) {
    case Axis::x:
      return Vec3::UnitZ();
    case Axis::y:
      return -Vec3::UnitZ();
    case Axis::z:
      return Vec3::UnitY();
  }
  return Vec3::UnitY();
}

namespace {

float finite_float(double value) {
  if (std::isnan(value)) return 0.0f;
  constexpr double largest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(value, -largest, largest));
}

// A triangle projected into pixel coordinates, in which pixel centres are integers and y grows
// downwards.
struct PixelTriangle {
  double ax, ay, e1x, e1y, e2x, e2y, area2;

  PixelTriangle(const TriangleMesh& mesh, const Triangle& t, const MapView& view) {
    const Vec3 u_axis = map_u_axis(view.up), v_axis = map_v_axis(view.up);
    const double inv = 1.0 / view.pixel_size;
    double x[3], y[3];
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions[t[k]];
      x[k] = (p.dot(u_axis) - view.box.u_min) * inv - 0.5;
      y[k] = (view.box.v_max - p.dot(v_axis)) * inv - 0.5;
    }
    ax = x[0], ay = y[0];
    e1x = x[1] - ax, e1y = y[1] - ay, e2x = x[2] - ax, e2y = y[2] - ay;
    // Twice the signed area; the y flip makes faces with n·up > 0 negative.
    area2 = e1x * e2y - e1y * e2x;
  }
  // Weights of corners 1 and 2 at pixel (x, y): signed areas of the sub-triangles opposite them.
  std::pair<double, double> weights(int x, int y) const {
    const double px = x - ax, py = y - ay;
    return {(px * e2y - py * e2x) / area2, (e1x * py - e1y * px) / area2};
  }
};

struct Coverage {
  std::vector<std::int32_t> face;  // -1: not covered
  std::vector<float> w1, w2;       // barycentric weights of corners 1 and 2 in that face
  std::vector<double> depth;       // interpolated height of that face
};

Coverage cover_pixels(const TriangleMesh& mesh, std::span<const std::uint8_t> free_surface,
                      const MapView& view) {
  const std::size_t pixels = static_cast<std::size_t>(view.width) * view.height;
  Coverage c;
  c.face.assign(pixels, -1);
  c.w1.assign(pixels, 0.0f);
  c.w2.assign(pixels, 0.0f);
  c.depth.assign(pixels, -std::numeric_limits<double>::infinity());
  const int up = static_cast<int>(view.up);
  constexpr double tolerance = -1e-9;  // relative: keeps pixel centres on shared edges

  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    if (!on_mapped_surface(free_surface, t)) continue;
    const PixelTriangle tri(mesh, t, view);
    if (!(tri.area2 < 0.0)) continue;  // faces down, edge-on, degenerate or NaN
    const double xs[3] = {tri.ax, tri.ax + tri.e1x, tri.ax + tri.e2x};
    const double ys[3] = {tri.ay, tri.ay + tri.e1y, tri.ay + tri.e2y};
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({xs[0], xs[1], xs[2]}))));
    const int x1 =
        std::min(view.width - 1, static_cast<int>(std::floor(std::max({xs[0], xs[1], xs[2]}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({ys[0], ys[1], ys[2]}))));
    const int y1 =
        std::min(view.height - 1, static_cast<int>(std::floor(std::max({ys[0], ys[1], ys[2]}))));
    const double h0 = mesh.positions[t[0]][up], h1 = mesh.positions[t[1]][up],
                 h2 = mesh.positions[t[2]][up];
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const auto [w1, w2] = tri.weights(x, y);
        const double w0 = 1.0 - w1 - w2;
        if (w0 < tolerance || w1 < tolerance || w2 < tolerance) continue;
        const double height = w0 * h0 + w1 * h1 + w2 * h2;
        const std::size_t i = static_cast<std::size_t>(y) * view.width + x;
        if (!(height > c.depth[i])) continue;
        c.depth[i] = height;
        c.face[i] = static_cast<std::int32_t>(f);
        c.w1[i] = static_cast<float>(w1);
        c.w2[i] = static_cast<float>(w2);
      }
    }
  }
  return c;
}

}  // namespace

TopDownMap rasterize_top_down(const TriangleMesh& surface, const CurvatureField& curvature,
                              std::span<const std::int8_t> label,
                              std::span<const std::uint8_t> free_surface, const MapView& view) {
  TopDownMap map;
  map.view = view;
  const std::size_t pixels = static_cast<std::size_t>(view.width) * view.height;
  for (auto* channel :
       {&map.height, &map.gaussian, &map.mean, &map.k1, &map.k2, &map.label, &map.alpha})
    channel->assign(pixels, 0.0f);
  if (pixels == 0) return map;

  const Coverage c = cover_pixels(surface, free_surface, view);
  const std::size_t workers = chunk_count(pixels, 1 << 18);
  std::vector<std::size_t> covered(workers, 0);
  parallel_chunks(pixels, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      if (c.face[i] < 0) continue;
      const Triangle& t = surface.triangles[c.face[i]];
      const double w1 = std::clamp<double>(c.w1[i], 0.0, 1.0);
      const double w2 = std::clamp<double>(c.w2[i], 0.0, 1.0);
      const double w0 = std::max(0.0, 1.0 - w1 - w2);
      auto blend = [&](const std::vector<double>& v) {
        return finite_float(w0 * v[t[0]] + w1 * v[t[1]] + w2 * v[t[2]]);
      };
      map.height[i] = finite_float(c.depth[i]);
      map.gaussian[i] = blend(curvature.gaussian);
      map.mean[i] = blend(curvature.mean);
      const PrincipalCurvatures k[3] = {
          principal_curvatures(curvature.gaussian[t[0]], curvature.mean[t[0]]),
          principal_curvatures(curvature.gaussian[t[1]], curvature.mean[t[1]]),
          principal_curvatures(curvature.gaussian[t[2]], curvature.mean[t[2]])};
      map.k1[i] = finite_float(w0 * k[0].k1 + w1 * k[1].k1 + w2 * k[2].k1);
      map.k2[i] = finite_float(w0 * k[0].k2 + w1 * k[1].k2 + w2 * k[2].k2);
      const int nearest = w0 >= w1 && w0 >= w2 ? 0 : (w1 >= w2 ? 1 : 2);
      map.label[i] = label.empty() ? 0.0f : static_cast<float>(label[t[nearest]]);
      map.alpha[i] = 1.0f;
      ++covered[worker];
    }
  });
  for (std::size_t n : covered) map.covered_pixels += n;
  return map;
}

}  // namespace toonwater
