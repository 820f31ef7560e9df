#include "scene/water_body.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "analyzer/edge_length.hpp"
#include "scene/level_split.hpp"
#include "scene/mesh2_writer.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace toonwater {
namespace {

constexpr double free_surface_share = 0.5;
// A face that reaches across no more than this many median edge lengths is a step of the mesh.
constexpr double max_cell_edges = 2.0;

double area(const SceneMesh& mesh, const Triangle& t) {
  const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
  return 0.5 * (b - a).cross(c - a).norm();
}

// The face's least height, 2·area / its longest edge: how far it reaches across.
double least_height(const SceneMesh& mesh, const Triangle& t) {
  const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
  const double longest =
      std::sqrt(std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()}));
  return 2.0 * area(mesh, t) / longest;
}

// Per face: the root of its region, the faces of its kind connected to it through shared
// corners.
std::vector<std::int32_t> regions_of_kind(const SceneMesh& mesh, const std::vector<bool>& upward) {
  DisjointSets regions(mesh.triangles.size());
  // Per vertex and kind, the first face of that kind met at the vertex.
  std::vector<std::array<std::int32_t, 2>> first_face(mesh.positions.size(), {-1, -1});
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    for (const std::int32_t v : mesh.triangles[f]) {
      std::int32_t& first = first_face[static_cast<std::size_t>(v)][upward[f] ? 1 : 0];
      if (first < 0)
        first = static_cast<std::int32_t>(f);
      else
        regions.join(first, static_cast<std::int32_t>(f));
    }
  std::vector<std::int32_t> root(mesh.triangles.size());
  for (std::size_t f = 0; f < root.size(); ++f)
    root[f] = regions.root(static_cast<std::int32_t>(f));
  return root;
}

}  // namespace

std::vector<double> upward_angle_shares(const SceneMesh& mesh, const std::vector<bool>& upward) {
  std::vector<double> share(mesh.positions.size(), 0.0), total(mesh.positions.size(), 0.0);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    for (int k = 0; k < 3; ++k) {
      const Vec3& p = mesh.positions[t[k]];
      const Vec3 e1 = mesh.positions[t[(k + 1) % 3]] - p, e2 = mesh.positions[t[(k + 2) % 3]] - p;
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      total[t[k]] += angle;
      if (upward[f]) share[t[k]] += angle;
    }
  }
  for (std::size_t v = 0; v < share.size(); ++v)
    share[v] = total[v] > 0 ? share[v] / total[v] : 0.0;
  return share;
}

std::vector<bool> cut_free_surface_from_body(PreparedSurface& surface,
                                             std::vector<TextureCoordinate>& uv) {
  const SceneMesh& mesh = surface.mesh;
  const std::vector<bool> upward = upward_faces(mesh);
  const std::vector<double> share = upward_angle_shares(mesh, upward);
  const double cell = median_edge_length(mesh.positions, mesh.triangles);
  const auto corners_side = [&](const Triangle& t) { return share[t[0]] > free_surface_share; };
  const auto crossed = [&](const Triangle& t) {
    return corners_side(t) != (share[t[1]] > free_surface_share) ||
           corners_side(t) != (share[t[2]] > free_surface_share);
  };
  // The largest region of each kind is never taken away whole: on a mesh too coarse for the
  // iso-line (a box of twelve faces, whose top's corners are all the box's corners) it stays
  // as its faces are.
  const std::vector<std::int32_t> region = regions_of_kind(mesh, upward);
  std::vector<double> region_area(mesh.triangles.size(), 0.0);
  std::vector<bool> region_left(mesh.triangles.size(), false);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    region_area[region[f]] += area(mesh, t);
    if (crossed(t) || corners_side(t) == upward[f]) region_left[region[f]] = true;
  }
  std::array<std::int32_t, 2> largest{-1, -1};
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    std::int32_t& l = largest[upward[f] ? 1 : 0];
    if (l < 0 || region_area[region[f]] > region_area[l]) l = region[f];
  }
  const auto may_change_side = [&](std::size_t f) {
    return region_left[region[f]] || region[f] != largest[upward[f] ? 1 : 0];
  };
  // The side of a face the iso-line does not cross.
  std::vector<bool> uncut_side(mesh.triangles.size());
  for (std::size_t f = 0; f < uncut_side.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    uncut_side[f] = least_height(mesh, t) <= max_cell_edges * cell && may_change_side(f)
                        ? corners_side(t)
                        : static_cast<bool>(upward[f]);
  }
  return split_at_level(surface, uv, share, free_surface_share, uncut_side);
}

}  // namespace toonwater
