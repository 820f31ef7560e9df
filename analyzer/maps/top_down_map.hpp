// A top-down map of a surface: an orthographic view along the up axis, rasterised from the
// triangles with barycentric interpolation of per-vertex values, topmost layer winning where
// the surface overlaps itself. Only faces with n·up > 0 are drawn, and, given a free-surface
// selection (FlowRegions::free_surface, free_surface.hpp), only faces whose three corners are
// on the free surface: a closed liquid volume (walls, floor, the fillets between them and the
// water, the floor of a cavity under an object) maps only its free surface.
//
// Map axes, right-handed and seen from above (u × v = up): columns run along u to the right,
// rows along v downwards (row 0 is v_max):
//   up = z: u = +x, v = +y        up = y: u = +x, v = −z        up = x: u = +y, v = +z
// (up = y is what a Y-up export of a Z-up scene gives, so both show the same top view.)
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace toonwater {

// A rectangle in the map plane (u, v).
struct MapBox {
  double u_min = 0, v_min = 0, u_max = 0, v_max = 0;
};

// Where the map's pixels lie: pixel (column i, row j) is centred on
// u = box.u_min + (i + ½)·pixel_size, v = box.v_max − (j + ½)·pixel_size.
struct MapView {
  Axis up = Axis::y;
  MapBox box;
  int width = 0, height = 0;
  double pixel_size = 0;
};

// Unit directions of the map's u and v axes in world space for an up axis (see above).
Vec3 map_u_axis(Axis up);
Vec3 map_v_axis(Axis up);

// Row-major width × height channels. Outside the surface every channel is 0 and alpha is 0.
struct TopDownMap {
  MapView view;
  std::vector<float> height;    // world coordinate along the up axis
  std::vector<float> gaussian;  // K
  std::vector<float> mean;      // H
  std::vector<float> k1, k2;
  std::vector<float> label;  // -1 valley, 0 none, 1 ridge: the nearest corner's label
  std::vector<float> alpha;  // 1 on the surface, 0 outside
  std::size_t covered_pixels = 0;
};

// Whether a face is drawn, apart from facing up: all corners selected, or no selection.
inline bool on_mapped_surface(std::span<const std::uint8_t> free_surface, const Triangle& t) {
  return free_surface.empty() || (free_surface[t[0]] && free_surface[t[1]] && free_surface[t[2]]);
}

// Curvature, labels and the free-surface selection are per vertex of `surface` (as in
// Analysis); an empty selection draws every upward face. Values beyond float's range are
// clamped to it, so the map holds no Inf or NaN.
TopDownMap rasterize_top_down(const TriangleMesh& surface, const CurvatureField& curvature,
                              std::span<const std::int8_t> label,
                              std::span<const std::uint8_t> free_surface, const MapView& view);

}  // namespace toonwater
