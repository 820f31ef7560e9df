// The free surface of a liquid mesh: the part that carries flow regions, maps and thresholds.
//
// Simulation meshes are often closed volumes (free surface plus the tank's walls and floor),
// and the liquid wraps around submerged objects. A vertex is on the free surface when
//   1. all its faces, and all its neighbours' faces, face up (n·up > min_up_component): walls
//      and floor fail, and so does the one ring next to them, where marching cubes rounds the
//      corner between wall and water into a strongly curved fillet;
//   2. its connected patch of such vertices is the largest one, or lies near or above the rest
//      level (its median height no more than `max_depth` below it) and has at least
//      `min_patch_vertices` vertices: the floor of a cavity under a floating object is dropped;
//      crests cut off by steep fronts and detached droplets big enough are kept.
// The rest level is given, or the median height of the largest patch.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace toonwater {

// Faces steeper than 60° are not free surface (the default of FreeSurfaceOptions, and the
// vertex normals povgen takes for the water line).
constexpr double free_surface_min_up_component = 0.5;

// The outline shell of a closed volume's top (povgen's mesh2_writer) takes faces far below the
// free surface's slope: it must reach round the rounded edge between the water and the tank's
// walls up to where it turns away from the camera, or the volume's back and side silhouettes
// lose their outline. (Shell faces from the free-surface selection, with or without its
// one-ring border, dropped them on the Mantaflow wake.)
constexpr double shell_min_up_component = 0.1;

struct FreeSurfaceOptions {
  Axis up = Axis::y;
  double min_up_component = free_surface_min_up_component;
  std::optional<double> rest_height;    // default: median height of the largest patch
  double max_depth = 2.0;               // in median edge lengths below the rest level
  std::size_t min_patch_vertices = 16;  // smaller detached patches (droplets) carry no flow
};

struct FreeSurface {
  std::vector<std::uint8_t> selected;  // per vertex: 1 on the free surface
  // Per vertex: 1 where selected and off the free surface's border ring: no face of the vertex
  // (faces with a repeated corner are none, topology.hpp) has a corner off the free surface.
  std::vector<std::uint8_t> inside;
  std::size_t vertices = 0;  // selected vertices
  std::size_t patches_kept = 0;
  std::size_t patches_dropped = 0;  // too deep or too small
  double rest_height = 0.0;
  double edge_length = 0.0;  // the median edge length (edge_length.hpp), max_depth's unit
};

FreeSurface select_free_surface(const TriangleMesh& mesh, const FreeSurfaceOptions& options);

}  // namespace toonwater
