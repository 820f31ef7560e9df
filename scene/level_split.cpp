#include "scene/level_split.hpp"

#include "analyzer/topology.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace toonwater {
namespace {

// The surface's per-vertex data, grown by one interpolated value per cut point.
struct VertexData {
  PreparedSurface& surface;
  std::vector<TextureCoordinate>& uv;

  int interpolate(int a, int b, double t) {
    SceneMesh& mesh = surface.mesh;
    mesh.positions.push_back((1 - t) * mesh.positions[a] + t * mesh.positions[b]);
    const Vec3 normal = (1 - t) * mesh.normals[a] + t * mesh.normals[b];
    // Opposite unit normals are never the two ends of an edge of a valid surface; were they,
    // the nearer end's normal stands in.
    mesh.normals.push_back(normal.norm() > 0 ? Vec3(normal.normalized())
                                             : mesh.normals[t < 0.5 ? a : b]);
    for (std::vector<double>* values : {&surface.flow_field, &surface.view_values})
      if (!values->empty()) values->push_back((1 - t) * (*values)[a] + t * (*values)[b]);
    if (!uv.empty()) {
      const auto mix = [&](int k) { return static_cast<float>((1 - t) * uv[a][k] + t * uv[b][k]); };
      uv.push_back({mix(0), mix(1)});
    }
    return static_cast<int>(mesh.positions.size() - 1);
  }
};

}  // namespace

std::vector<bool> split_at_level(PreparedSurface& surface, std::vector<TextureCoordinate>& uv,
                                 std::span<const double> field, double level,
                                 const std::vector<bool>& uncut_side) {
  SceneMesh& mesh = surface.mesh;
  const std::size_t vertices = mesh.positions.size();
  if (field.size() != vertices || !(uv.empty() || uv.size() == vertices))
    throw std::logic_error("split_at_level: one field value and texture coordinate per vertex");
  if (!(uncut_side.empty() || uncut_side.size() == mesh.triangles.size()))
    throw std::logic_error("split_at_level: one side per face");
  const auto above = [&](int v) { return field[static_cast<std::size_t>(v)] > level; };
  VertexData data{surface, uv};
  // The cut point of edge {a, b}, made once for both its faces.
  std::unordered_map<std::uint64_t, int> cut_points;
  const auto cut = [&](int a, int b) {
    const auto [it, made] = cut_points.try_emplace(edge_key(a, b), -1);
    if (made) {
      // Parametrised from the lower index, so that both faces compute the same point.
      const int from = std::min(a, b), to = std::max(a, b);
      const double t = (level - field[from]) / (field[to] - field[from]);
      it->second = t < level_split_margin         ? from
                   : t > 1.0 - level_split_margin ? to
                                                  : data.interpolate(from, to, t);
    }
    return it->second;
  };

  std::vector<Triangle> triangles;
  std::vector<bool> face_above;
  triangles.reserve(mesh.triangles.size());
  face_above.reserve(mesh.triangles.size());
  const auto add = [&](const Triangle& t, bool is_above) {
    if (has_repeated_corner(t)) return;  // a cut point snapped to a corner
    triangles.push_back(t);
    face_above.push_back(is_above);
  };
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& face = mesh.triangles[f];
    const std::array<bool, 3> side{above(face[0]), above(face[1]), above(face[2])};
    if (side[0] == side[1] && side[1] == side[2]) {
      add(face, uncut_side.empty() ? side[0] : uncut_side[f]);
      continue;
    }
    // The corner alone on its side first, keeping the face's winding.
    int lone = 0;
    while (side[lone] == side[(lone + 1) % 3] || side[lone] == side[(lone + 2) % 3]) ++lone;
    const int a = face[lone], b = face[(lone + 1) % 3], c = face[(lone + 2) % 3];
    const int ab = cut(a, b), ac = cut(a, c);
    add({a, ab, ac}, side[lone]);
    // The quad ab, b, c, ac on the other side, by the diagonal that leaves no piece flat: with
    // ab snapped onto a, ac lies on the edge from a to c.
    if (ab == a) {
      add({ab, b, ac}, !side[lone]);
      add({b, c, ac}, !side[lone]);
    } else {
      add({ab, b, c}, !side[lone]);
      add({ab, c, ac}, !side[lone]);
    }
  }
  mesh.triangles = std::move(triangles);
  return face_above;
}

}  // namespace toonwater
