#include "sim/water_figure.hpp"

#include "sim/mesh_builders.hpp"

#include <cmath>
#include <numbers>

namespace toonwater::sim {
namespace {

constexpr double pi = std::numbers::pi;
const Vec3 semi_axes(1.0, 0.5, 0.42);
constexpr double amplitude = 0.06, wavenumber = 2 * pi, angular_frequency = 3 * pi;

}  // namespace

double water_figure_period() { return 2 * pi / angular_frequency; }

TriangleMesh water_figure_body(double time, int segments) {
  TriangleMesh body = uv_sphere(Vec3::Zero(), 1.0, std::max(2, segments / 2), segments);
  for (Vec3& p : body.positions) {
    const Vec3 on_ellipsoid = p.cwiseProduct(semi_axes);
    const double swell =
        1.0 + amplitude * (1.0 - p.x() * p.x()) *
                  std::sin(wavenumber * on_ellipsoid.x() - angular_frequency * time);
    p = on_ellipsoid * swell;
  }
  return body;
}

TriangleMesh water_figure_bones(int segments) {
  const int s = std::max(6, segments / 4);
  TriangleMesh bones = uv_sphere(Vec3(0.62, 0.05, 0.0), 0.14, s / 2 + 1, s);    // skull
  append(bones, capsule(Vec3(-0.75, 0.0, 0.0), Vec3(0.5, 0.0, 0.0), 0.03, s));  // spine
  for (double x : {-0.35, -0.15, 0.05, 0.25})
    for (double side : {-1.0, 1.0})
      append(bones, capsule(Vec3(x, 0.0, 0.0), Vec3(x - 0.08, -0.3, 0.22 * side), 0.022, s));
  for (double side : {-1.0, 1.0})  // tail fin
    append(bones, capsule(Vec3(-0.75, 0.0, 0.0), Vec3(-0.9, 0.12 * side, 0.0), 0.022, s));
  return bones;
}

}  // namespace toonwater::sim
