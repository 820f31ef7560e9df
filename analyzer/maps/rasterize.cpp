// Top-down rasteriser (see top_down_map.hpp). Two passes over flat arrays:
//  1. coverage: each upward-facing triangle, projected on the map plane, visits the pixel
//     centres inside it (edge functions, inclusive so shared edges leave no cracks) and keeps
//     the face and barycentric coordinates of the highest point seen so far (a depth test on
//     the interpolated height: the topmost layer wins);
//  2. resolve: every covered pixel interpolates the values of its face's corners with those
//     barycentric weights, once, however much overdraw there was. Labels are categorical, so a
//     pixel takes the label of its nearest corner (largest weight) instead of a blend.
#include "analyzer/maps/top_down_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace toonwater {

Vec3 map_u_axis(Axis up) { return up == Axis::x ? Vec3::UnitY() : Vec3::UnitX(); }

Vec3 map_v_axis(Axis up) {
  switch (up) {
    case Axis::x: return Vec3::UnitZ();
    case Axis::y: return -Vec3::UnitZ();
    case Axis::z: return Vec3::UnitY();
  }
  return Vec3::UnitY();
}

namespace {

float finite_float(double value) {
  if (std::isnan(value)) return 0.0f;
  constexpr double largest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(value, -largest, largest));
}

struct Coverage {
  std::vector<std::int32_t> face;  // -1: not covered
  std::vector<float> w1, w2;       // barycentric weights of corners 1 and 2
  std::vector<double> depth;       // interpolated height
};

Coverage cover_pixels(const TriangleMesh& mesh, const MapView& view) {
  const std::size_t pixels = static_cast<std::size_t>(view.width) * view.height;
  Coverage c;
  c.face.assign(pixels, -1);
  c.w1.assign(pixels, 0.0f);
  c.w2.assign(pixels, 0.0f);
  c.depth.assign(pixels, -std::numeric_limits<double>::infinity());

  const Vec3 u_axis = map_u_axis(view.up), v_axis = map_v_axis(view.up);
  const int up = static_cast<int>(view.up);
  const double inv = 1.0 / view.pixel_size;
  // Pixel coordinates in which pixel centres are integers; y grows downwards.
  auto to_pixel = [&](const Vec3& p) {
    return Eigen::Vector2d((p.dot(u_axis) - view.box.u_min) * inv - 0.5,
                           (view.box.v_max - p.dot(v_axis)) * inv - 0.5);
  };
  constexpr double tolerance = -1e-9;  // relative: keeps pixel centres on shared edges

  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Vec3 &p0 = mesh.positions[t[0]], &p1 = mesh.positions[t[1]], &p2 = mesh.positions[t[2]];
    const Eigen::Vector2d a = to_pixel(p0), b = to_pixel(p1), d = to_pixel(p2);
    // Twice the signed area in pixel space; the y flip makes upward faces negative.
    const double area2 = (b - a).x() * (d - a).y() - (b - a).y() * (d - a).x();
    if (!(area2 < 0.0)) continue;  // faces down, edge-on, degenerate or NaN
    const int x0 = std::max(0, static_cast<int>(std::ceil(std::min({a.x(), b.x(), d.x()}))));
    const int x1 = std::min(view.width - 1, static_cast<int>(std::floor(std::max({a.x(), b.x(), d.x()}))));
    const int y0 = std::max(0, static_cast<int>(std::ceil(std::min({a.y(), b.y(), d.y()}))));
    const int y1 = std::min(view.height - 1, static_cast<int>(std::floor(std::max({a.y(), b.y(), d.y()}))));
    if (x0 > x1 || y0 > y1) continue;
    const double inv_area = 1.0 / area2;
    const double h0 = p0[up], h1 = p1[up], h2 = p2[up];
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        // Barycentric weight of corner k: signed area of the sub-triangle opposite it.
        const double px = x - a.x(), py = y - a.y();
        const double w1 = (px * (d - a).y() - py * (d - a).x()) * inv_area;
        const double w2 = ((b - a).x() * py - (b - a).y() * px) * inv_area;
        const double w0 = 1.0 - w1 - w2;
        if (w0 < tolerance || w1 < tolerance || w2 < tolerance) continue;
        const double height = w0 * h0 + w1 * h1 + w2 * h2;
        const std::size_t i = static_cast<std::size_t>(y) * view.width + x;
        if (!(height > c.depth[i])) continue;
        c.depth[i] = height;
        c.face[i] = static_cast<std::int32_t>(f);
        c.w1[i] = static_cast<float>(std::clamp(w1, 0.0, 1.0));
        c.w2[i] = static_cast<float>(std::clamp(w2, 0.0, 1.0));
      }
    }
  }
  return c;
}

}  // namespace

TopDownMap rasterize_top_down(const TriangleMesh& surface, const CurvatureField& curvature,
                              std::span<const std::int8_t> label, const MapView& view) {
  TopDownMap map;
  map.view = view;
  const std::size_t pixels = static_cast<std::size_t>(view.width) * view.height;
  for (auto* channel : {&map.height, &map.gaussian, &map.mean, &map.k1, &map.k2, &map.label,
                        &map.alpha})
    channel->assign(pixels, 0.0f);
  if (pixels == 0) return map;

  const Coverage c = cover_pixels(surface, view);
  for (std::size_t i = 0; i < pixels; ++i) {
    if (c.face[i] < 0) continue;
    const Triangle& t = surface.triangles[c.face[i]];
    const double w1 = c.w1[i], w2 = c.w2[i], w0 = std::max(0.0, 1.0 - w1 - w2);
    auto blend = [&](const std::vector<double>& v) {
      return finite_float(w0 * v[t[0]] + w1 * v[t[1]] + w2 * v[t[2]]);
    };
    map.height[i] = finite_float(c.depth[i]);
    map.gaussian[i] = blend(curvature.gaussian);
    map.mean[i] = blend(curvature.mean);
    map.k1[i] = blend(curvature.k1);
    map.k2[i] = blend(curvature.k2);
    const int nearest = w0 >= w1 && w0 >= w2 ? 0 : (w1 >= w2 ? 1 : 2);
    map.label[i] = label.empty() ? 0.0f : static_cast<float>(label[t[nearest]]);
    map.alpha[i] = 1.0f;
    ++map.covered_pixels;
  }
  return map;
}

}  // namespace toonwater
