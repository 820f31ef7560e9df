#include "scene/scene_mesh.hpp"

#include "analyzer/geometry_tolerances.hpp"
#include "scene/axes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace toonwater {

SceneMesh make_scene_mesh(const TriangleMesh& surface, std::span<const Vec3> normals, bool closed,
                          Axis up) {
  SceneMesh out;
  out.closed = closed;
  const std::size_t n = surface.positions.size();
  if (normals.size() != n)
    throw std::logic_error("make_scene_mesh: one normal per vertex expected");
  out.triangles.reserve(surface.triangles.size());
  for (const Triangle& t : surface.triangles) {
    if (is_degenerate_triangle(surface.positions[t[0]], surface.positions[t[1]],
                               surface.positions[t[2]]))
      ++out.degenerate_faces;
    else
      out.triangles.push_back(t);
  }

  std::vector<Vec3> normal(normals.begin(), normals.end());
  std::vector<bool> missing(n);
  for (std::size_t v = 0; v < n; ++v) {
    missing[v] = !(normal[v].squaredNorm() > 0.5);  // unit normals only; zero means undefined
    out.replaced_normals += missing[v];
  }
  if (out.replaced_normals > 0) {
    for (const Triangle& t : out.triangles) {
      if (!missing[t[0]] && !missing[t[1]] && !missing[t[2]]) continue;
      const Vec3 face = (surface.positions[t[1]] - surface.positions[t[0]])
                            .cross(surface.positions[t[2]] - surface.positions[t[0]]);
      for (int k : t)
        if (missing[k]) normal[k] += face;  // area-weighted mean face normal
    }
    Vec3 up_axis = Vec3::Zero();
    up_axis[static_cast<int>(up)] = 1.0;
    for (std::size_t v = 0; v < n; ++v) {
      if (!missing[v]) continue;
      const double length = normal[v].norm();
      normal[v] = length > 0.0 && std::isfinite(length) ? Vec3(normal[v] / length) : up_axis;
    }
  }

  out.positions.resize(n);
  out.normals.resize(n);
  for (std::size_t v = 0; v < n; ++v) {
    out.positions[v] = to_povray(surface.positions[v], up);
    out.normals[v] = to_povray(normal[v], up);
  }
  if (n > 0) {
    out.min = out.max = out.positions[0];
    for (const Vec3& p : out.positions) {
      out.min = out.min.cwiseMin(p);
      out.max = out.max.cwiseMax(p);
    }
  }
  return out;
}

double band_coordinate(double l_dot_n) { return 0.5 + 0.4999 * std::clamp(l_dot_n, -1.0, 1.0); }

double flow_coordinate(double field) {
  constexpr double field_limit = 4.0, scale = 0.12;  // v in [0.02, 0.98]
  return 0.5 + scale * std::clamp(std::isfinite(field) ? field : 0.0, -field_limit, field_limit);
}

int toon_class(const ToonLimits& limits, const TextureCoordinate& c) {
  if (limits.flow && c[1] <= limits.flow->first) return limits.valley();
  if (limits.flow && c[1] >= limits.flow->second) return limits.ridge();
  return static_cast<int>(std::lower_bound(limits.bands.begin(), limits.bands.end(), c[0]) -
                          limits.bands.begin());
}

std::vector<TextureCoordinate> toon_coordinates(const SceneMesh& mesh, const LightGeometry& light,
                                                std::span<const double> flow_field) {
  const std::size_t n = mesh.positions.size();
  std::vector<TextureCoordinate> uv(n);
  for (std::size_t v = 0; v < n; ++v) {
    Vec3 to_light = light.vector;
    if (!light.parallel) {
      to_light -= mesh.positions[v];
      const double length = to_light.norm();
      to_light = length > 0.0 ? Vec3(to_light / length) : mesh.normals[v];
    }
    const double v_coordinate = flow_field.empty() ? 0.5 : flow_coordinate(flow_field[v]);
    uv[v] = {static_cast<float>(band_coordinate(to_light.dot(mesh.normals[v]))),
             static_cast<float>(v_coordinate)};
  }
  return uv;
}

std::vector<TextureCoordinate> value_coordinates(std::span<const double> values, double range) {
  std::vector<TextureCoordinate> uv(values.size());
  for (std::size_t v = 0; v < values.size(); ++v) {
    const double t = range > 0.0 ? std::clamp(values[v] / range, -1.0, 1.0) : 0.0;
    uv[v] = {static_cast<float>(0.5 + 0.4999 * (std::isfinite(t) ? t : 0.0)), 0.5f};
  }
  return uv;
}

}  // namespace toonwater
