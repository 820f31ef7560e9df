// The camera of scene.pov as a pinhole: where a point shows in the image, and how wide a
// pixel is at a point, for what is sized in pixels at the camera (droplets, foam).
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_writer.hpp"

#include <Eigen/Core>

#include <optional>

namespace toonwater {

// The camera as a pinhole on an image `width` × `height` pixels with square pixels (what
// scene.pov's camera block makes of a CameraPlacement): pixel (0, 0) at the top left.
struct ScreenProjection {
  Vec3 location = Vec3::Zero(), right = Vec3::UnitX(), up = Vec3::UnitY(), forward = Vec3::UnitZ();
  double focal_pixels = 1.0;  // the image's half-width over tan(angle / 2)
  int width = 1, height = 1;

  // The pixel `p` projects to; none behind the camera.
  std::optional<Eigen::Vector2d> pixel(const Vec3& p) const;
  // The width of a pixel at p's distance from the camera, in world units.
  double pixel_size(const Vec3& p) const;
};

ScreenProjection screen_projection(const CameraPlacement& camera, int width, int height);

}  // namespace toonwater
