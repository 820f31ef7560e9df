// A surface made ready for POV-Ray: in POV-Ray's frame (axes.hpp), with a valid unit normal at
// every vertex, without degenerate faces, and with the per-vertex texture coordinates the toon
// shader reads (povray-notes.md, "Three crisp bands"):
//
//   u = 0.5 + 0.4999 · clamp(L·n, −1, 1)        L = unit vector from the vertex to the light
//   v = 0.5 + 0.12 · clamp(s, −4, 4)             s: the flow field (flow_regions.hpp)
//
// POV-Ray interpolates u and v linearly inside each triangle and evaluates the colour map per
// pixel, so band and flow-region boundaries are crisp at pixel level, and a flow region's edge,
// the iso-line s = ±1 (v = 0.5 ± 0.12), is a smooth curve across the triangles rather than a
// staircase along their edges. u and v stay inside (0, 1) because gradient patterns wrap modulo
// 1; clamping s at ±4 changes no boundary where the field varies less than 4 between neighbours.
#pragma once

#include "analyzer/mesh.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <utility>
#include <vector>

namespace toonwater {

struct SceneMesh {
  std::vector<Vec3> positions;       // POV-Ray frame
  std::vector<Vec3> normals;         // unit length, POV-Ray frame
  std::vector<Triangle> triangles;   // non-degenerate faces only (geometry_tolerances.hpp)
  bool closed = false;               // no boundary or non-manifold edge: has an inside
  std::size_t degenerate_faces = 0;  // left out
  std::size_t replaced_normals = 0;  // zero normals replaced by a face normal (or up)
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();  // bounding box

  double diagonal() const { return (max - min).norm(); }
};

// `normals` are per vertex of `surface` in the input's frame and may contain zero vectors
// (undefined curvature, isolated vertices): they are replaced by the mean normal of the
// vertex's faces, or by the up axis when it has none.
SceneMesh make_scene_mesh(const TriangleMesh& surface, std::span<const Vec3> normals, bool closed,
                          Axis up);

// The light as seen from a vertex, in POV-Ray's frame.
struct LightGeometry {
  bool parallel = true;
  Vec3 vector = Vec3(0, 1, 0);  // parallel: unit direction to the light; else its position
};

using TextureCoordinate = std::array<float, 2>;

// u of an L·n, and v of a flow field value, as above (the template's Toon_band_key and
// Toon_flow_key).
double band_coordinate(double l_dot_n);
double flow_coordinate(double field);

// The toon classes' limits on the coordinates: the bands' on u, ascending (band b where
// bands[b − 1] < u <= bands[b]), and, where flow regions are drawn, the valley's and the
// ridge's on v (valley where v <= flow->first, ridge where v >= flow->second).
struct ToonLimits {
  std::vector<double> bands;
  std::optional<std::pair<double, double>> flow;

  int valley() const { return static_cast<int>(bands.size()) + 1; }
  int ridge() const { return valley() + 1; }
};

// The class a vertex is painted in: its band, 0 to bands.size(), or valley() or ridge(). A
// region hides the band under it.
int toon_class(const ToonLimits& limits, const TextureCoordinate& c);

// (u, v) per vertex as above; `flow_field` may be empty (no flow regions: v = 0.5).
std::vector<TextureCoordinate> toon_coordinates(const SceneMesh& mesh, const LightGeometry& light,
                                                std::span<const double> flow_field);

// (u, 0.5) per vertex with u = 0.5 + 0.4999 * clamp(value / range, −1, 1): a curvature value
// for the curvature view's colour map (range > 0).
std::vector<TextureCoordinate> value_coordinates(std::span<const double> values, double range);

}  // namespace toonwater
