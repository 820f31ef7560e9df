// A prepared surface as a frame's include (see frame_include.hpp).
#include "scene/frame_include.hpp"

#include "analyzer/free_surface.hpp"
#include "scene/stroke_writer.hpp"
#include "scene/toon_islands.hpp"

#include <algorithm>
#include <optional>

namespace toonwater {

double water_line(const SceneMesh& water, const Vec3& lo, const Vec3& hi) {
  const Vec3 grow = 0.25 * (hi - lo);
  const double x0 = lo.x() - grow.x(), x1 = hi.x() + grow.x(), z0 = lo.z() - grow.z(),
               z1 = hi.z() + grow.z();
  // Faces, not vertices: a simplified calm surface is a few large faces whose corners all lie
  // outside a small object's footprint.
  std::vector<double> heights;
  for (const Triangle& t : water.triangles) {
    const Vec3 &a = water.positions[t[0]], &b = water.positions[t[1]], &c = water.positions[t[2]];
    const Vec3 normal = water.normals[t[0]] + water.normals[t[1]] + water.normals[t[2]];
    if (!(normal.y() > free_surface_min_up_component * normal.norm())) continue;
    if (std::max({a.x(), b.x(), c.x()}) < x0 || std::min({a.x(), b.x(), c.x()}) > x1 ||
        std::max({a.z(), b.z(), c.z()}) < z0 || std::min({a.z(), b.z(), c.z()}) > z1)
      continue;
    heights.push_back((a.y() + b.y() + c.y()) / 3.0);
  }
  if (heights.empty()) return lo.y() - (hi - lo).norm() - 1.0;
  const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
  std::nth_element(heights.begin(), middle, heights.end());
  return *middle;
}

std::string empty_water_include() {
  return "// Written by toonwater povgen: this frame's water mesh was empty.\n"
         "#declare Water_mesh = union {}\n"
         "#declare Water_shell = union {}\n";
}

std::vector<TextureCoordinate> texture_coordinates(const PreparedSurface& surface,
                                                   const LightGeometry& light) {
  return surface.view_values.empty() ? toon_coordinates(surface.mesh, light, surface.flow_field)
                                     : value_coordinates(surface.view_values, surface.view_range);
}

std::vector<TextureCoordinate> water_coordinates(const PreparedSurface& surface,
                                                 const LightGeometry& light,
                                                 const SceneLayout& layout) {
  std::vector<TextureCoordinate> uv = texture_coordinates(surface, light);
  const SceneConfig& config = *layout.config;
  // A curvature view shows the values as they are; min_patch = 0 keeps every patch.
  if (!surface.view_values.empty() || !(config.water.min_patch > 0.0)) return uv;
  IslandLimits island;
  island.radius_pixels = config.water.min_patch;
  merge_toon_islands(surface.mesh, layout.camera.location,
                     pixel_widths(surface.mesh, layout.camera, config.render.width),
                     water_toon_limits(layout), island, uv);
  return uv;
}

std::string mesh_include(const PreparedSurface& surface, const std::string& prefix,
                         std::span<const TextureCoordinate> uv,
                         std::span<const double> shell_offsets, const FaceTextures* textures,
                         const std::vector<bool>* shell_faces) {
  std::string text = "// Written by toonwater povgen: meshes for scene.pov.\n";
  append_mesh2(text, prefix + "_mesh", surface.mesh, uv, textures);
  if (!shell_offsets.empty())
    append_shell_mesh2(text, prefix + "_shell", surface.mesh, shell_offsets, shell_faces);
  append_flow_lines(text, surface.flow_lines);
  return text;
}

}  // namespace toonwater
