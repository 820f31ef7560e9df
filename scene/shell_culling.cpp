#include "scene/shell_culling.hpp"

#include "scene/mesh2_writer.hpp"

#include <algorithm>
#include <cmath>

namespace toonwater {
namespace {

// How far POV-Ray's copy of a written coordinate may be from ours, relative to the largest
// coordinate: half a unit of the 7th significant digit (5e-7) plus single precision (6e-8),
// rounded up.
constexpr double kPositionError = 1e-6;

// POV-Ray ignores a hit closer than this to a ray's start (scene units, MIN_ISECT_DEPTH), and a
// face whose shell lies less than ten times that above the water is never dropped.
constexpr double kPovrayMinimumDepth = 1e-4;
constexpr double kMinimumOffset = 10 * kPovrayMinimumDepth;

}  // namespace

bool shell_met_by_camera_rays_only(const SceneConfig& config, bool shell_no_reflection) {
  const WaterConfig& w = config.water;
  const bool toon =
      w.shading == WaterShading::toon;  // a curvature view neither reflects nor refracts
  const bool refracts = toon && w.transmit > 0;
  const bool reflects = toon && w.reflection > 0;
  return !refracts && (!reflects || shell_no_reflection);
}

std::vector<bool> shell_faces_seen_from_behind(const SceneMesh& mesh,
                                               std::span<const double> offsets, const Vec3& eye,
                                               std::span<const KeepOutBox> keep_out,
                                               const std::vector<bool>* keep) {
  const std::size_t n = mesh.positions.size();
  std::vector<Vec3> shell(n);
  double largest = eye.cwiseAbs().maxCoeff();
  for (std::size_t v = 0; v < n; ++v) {
    shell[v] = mesh.positions[v] + offsets[v] * mesh.normals[v];
    largest = std::max(largest, shell[v].cwiseAbs().maxCoeff());
  }
  const double delta = kPositionError * largest;
  std::vector<bool> seen(mesh.triangles.size(), false);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (keep && !(*keep)[f]) continue;
    const Triangle t = shell_winding(mesh, mesh.triangles[f]);
    const Vec3 &a = shell[t[0]], &b = shell[t[1]], &c = shell[t[2]];
    if (std::min({offsets[t[0]], offsets[t[1]], offsets[t[2]]}) < kMinimumOffset) {
      seen[f] = true;
      continue;
    }
    const Vec3 lo = a.cwiseMin(b).cwiseMin(c).array() - kMinimumOffset;
    const Vec3 hi = a.cwiseMax(b).cwiseMax(c).array() + kMinimumOffset;
    const bool near_object =
        std::any_of(keep_out.begin(), keep_out.end(), [&](const KeepOutBox& box) {
          return (lo.array() <= box.max.array()).all() && (hi.array() >= box.min.array()).all();
        });
    if (near_object) {
      seen[f] = true;
      continue;
    }
    const Vec3 ab = a - b, cb = c - b, to_eye = eye - a;
    const double front = to_eye.dot(ab.cross(cb));  // (E − a)·N
    // Moving each vertex (and the eye) by up to delta moves N by at most
    // 2δ(|a−b| + |c−b|) + 4δ² and E − a by at most 2δ, so (E − a)·N by at most this:
    const double n_error = 2 * delta * (ab.norm() + cb.norm()) + 4 * delta * delta;
    const double bound = 2 * delta * ab.cross(cb).norm() + (to_eye.norm() + 2 * delta) * n_error;
    seen[f] = !(front > 2 * bound);  // twice the bound: a margin for our own rounding
  }
  // The faces around the kept ones stay too (see the header: a front face beside a back face).
  std::vector<bool> near_seen(n, false);
  for (std::size_t f = 0; f < seen.size(); ++f)
    if (seen[f])
      for (const int v : mesh.triangles[f]) near_seen[v] = true;
  for (std::size_t f = 0; f < seen.size(); ++f) {
    if (keep && !(*keep)[f]) continue;
    const Triangle& t = mesh.triangles[f];
    seen[f] = near_seen[t[0]] || near_seen[t[1]] || near_seen[t[2]];
  }
  return seen;
}

}  // namespace toonwater
