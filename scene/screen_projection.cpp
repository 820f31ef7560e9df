// The camera as a pinhole; stated in screen_projection.hpp.
#include "scene/screen_projection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace toonwater {

std::optional<Eigen::Vector2d> ScreenProjection::pixel(const Vec3& p) const {
  const Vec3 d = p - location;
  const double depth = d.dot(forward);
  if (!(depth > 0.0)) return std::nullopt;
  return Eigen::Vector2d(0.5 * width + focal_pixels * d.dot(right) / depth,
                         0.5 * height - focal_pixels * d.dot(up) / depth);
}

double ScreenProjection::pixel_size(const Vec3& p) const {
  return (p - location).norm() / focal_pixels;
}

ScreenProjection screen_projection(const CameraPlacement& camera, int width, int height) {
  ScreenProjection s;
  s.location = camera.location;
  s.forward = (camera.look_at - camera.location).normalized();
  // POV-Ray's look_at: right is sky × direction with sky = +y (left-handed), up completes it.
  s.right = Vec3::UnitY().cross(s.forward).normalized();
  s.up = s.forward.cross(s.right);
  s.width = std::max(1, width);
  s.height = std::max(1, height);
  s.focal_pixels = 0.5 * s.width / std::tan(0.5 * camera.angle * std::numbers::pi / 180.0);
  return s;
}

}  // namespace toonwater
