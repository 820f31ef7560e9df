// A prepared surface as a frame's include: its texture coordinates, its mesh2 text (with its
// outline shell and flow strokes), and the water line an object in it meets.
#pragma once

#include "scene/mesh2_writer.hpp"
#include "scene/prepared_surface.hpp"
#include "scene/scene_mesh.hpp"
#include "scene/scene_writer.hpp"

#include <span>
#include <string>
#include <vector>

namespace toonwater {

// The texture coordinates written per vertex: toon coordinates, or the curvature view's values.
std::vector<TextureCoordinate> texture_coordinates(const PreparedSurface& surface,
                                                   const LightGeometry& light);
// The water's, as a frame is written for the scene's camera: its toon bands without the
// islands too small to draw (toon_islands.hpp).
std::vector<TextureCoordinate> water_coordinates(const PreparedSurface& surface,
                                                 const LightGeometry& light,
                                                 const SceneLayout& layout);

// The include of a frame whose water mesh is empty: the declarations, holding nothing.
std::string empty_water_include();

// The mesh2 include text: `Prefix_mesh` with the texture coordinates `uv` (and `textures` per
// face when given), and `Prefix_shell` when `shell_offsets` (one per vertex, world units) is not
// empty, of the faces `shell_faces` marks (all when null).
std::string mesh_include(const PreparedSurface& surface, const std::string& prefix,
                         std::span<const TextureCoordinate> uv,
                         std::span<const double> shell_offsets,
                         const FaceTextures* textures = nullptr,
                         const std::vector<bool>* shell_faces = nullptr);

// The height (POV-Ray's y) of the water line around an object whose box is [lo, hi] in a
// frame: the median height of the centroids of the free-surface faces (n·y > 0.5) that reach
// over the object's footprint in x and z (grown by a quarter of its size); below the object
// where no water is.
double water_line(const SceneMesh& water, const Vec3& lo, const Vec3& hi);

}  // namespace toonwater
