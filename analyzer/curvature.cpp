// Discrete curvature after Meyer, Desbrun, Schröder and Barr (2002); formulas in curvature.hpp.
//
// Robustness choices (see ../shared/design/curvature-notes.md for how other libraries fail):
// - Positions are scaled by a power of two so that the largest coordinate is of order one. The
//   scaling is exact, so K ∝ 1/s² and H ∝ 1/s hold to the last bit for power-of-two scales, and
//   coordinates near 1e±300 neither overflow nor underflow in the squared lengths.
// - Angles come from atan2(|u×v|, u·v), cotangents from (u·v)/|u×v| — never acos.
// - A face with a zero-length edge contributes nothing. A sliver — a face with an angle below
//   3° (so also a cap with an angle above 177°), or whose doubled area is below 1e-12 of its
//   longest squared edge — contributes its corner angles and, if it has an area, its normal,
//   but no area and no cotangent weights: its cotangents are dominated by round-off and one of
//   them can swamp a vertex's Laplacian (MeshLab returns H = 1e7 next to a collinear triangle;
//   pmp clamps cotangents at the same 3°). Its corners then lack part of their one-ring.
// - Boundary and non-manifold vertices and the corners of slivers have no complete one-ring:
//   at a boundary the angle deficit measures the geodesic curvature of the boundary (π − Σθ),
//   not a property of the surface. Their K and H are the mean of their computed neighbours'
//   values (status `extrapolated`), so a map of an open sheet has no spurious rim and a
//   marching-cubes sliver does not make a spike.
// - A vertex with no area or no usable normal, or whose values are not finite, gets zeros
//   (status `undefined`) and is counted.
#include "analyzer/curvature.hpp"

#include "analyzer/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace toonwater {
namespace {

constexpr double degenerate_area_ratio = 1e-12;
constexpr double sliver_cotangent = 19.08113668772821;  // cot(3°)

// 2^-e with e the binary exponent of the largest |coordinate|: multiplying by it is exact.
double power_of_two_scale(const std::vector<Vec3>& positions) {
  double largest = 0.0;
  for (const Vec3& p : positions) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (largest == 0.0 || !std::isfinite(largest)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(largest));
}

// Per-vertex sums over incident faces, one set per worker thread.
struct FaceSums {
  std::vector<double> area;
  std::vector<double> angle;
  std::vector<Vec3> laplacian;  // Σ (cot α + cot β)(xᵢ − xⱼ)
  std::vector<Vec3> normal;     // Σ θ n_face
  std::vector<std::uint8_t> at_sliver;  // a corner of a sliver face

  explicit FaceSums(std::size_t n)
      : area(n, 0.0),
        angle(n, 0.0),
        laplacian(n, Vec3::Zero()),
        normal(n, Vec3::Zero()),
        at_sliver(n, 0) {}
};

// Adds the contributions of faces [begin, end) to `sums`; returns how many were slivers or
// had a repeated corner or a zero-length edge.
std::size_t accumulate_faces(const TriangleMesh& mesh, double scale, std::size_t begin,
                             std::size_t end, FaceSums& sums) {
  std::size_t degenerate = 0;
  for (std::size_t f = begin; f < end; ++f) {
    const Triangle& t = mesh.triangles[f];
    if (has_repeated_corner(t)) {
      ++degenerate;
      continue;
    }
    const std::int32_t i = t[0], j = t[1], k = t[2];
    const Vec3 a = mesh.positions[i] * scale;
    const Vec3 b = mesh.positions[j] * scale;
    const Vec3 c = mesh.positions[k] * scale;
    const Vec3 ab = b - a, bc = c - b, ca = a - c;
    const double ab2 = ab.squaredNorm(), bc2 = bc.squaredNorm(), ca2 = ca.squaredNorm();
    if (ab2 == 0.0 || bc2 == 0.0 || ca2 == 0.0) {
      ++degenerate;
      continue;
    }
    const Vec3 cross = ab.cross(-ca);
    const double double_area = cross.norm();
    // Corner dot products: at i between ab and ac, at j between bc and ba, at k between ca and cb.
    const double dot_i = -ab.dot(ca), dot_j = -bc.dot(ab), dot_k = -ca.dot(bc);
    const double angle_i = std::atan2(double_area, dot_i);
    const double angle_j = std::atan2(double_area, dot_j);
    const double angle_k = std::atan2(double_area, dot_k);
    sums.angle[i] += angle_i;
    sums.angle[j] += angle_j;
    sums.angle[k] += angle_k;

    if (double_area <= degenerate_area_ratio * std::max({ab2, bc2, ca2})) {
      ++degenerate;
      sums.at_sliver[i] = sums.at_sliver[j] = sums.at_sliver[k] = 1;
      continue;
    }
    const Vec3 unit_normal = cross / double_area;
    sums.normal[i] += angle_i * unit_normal;
    sums.normal[j] += angle_j * unit_normal;
    sums.normal[k] += angle_k * unit_normal;
    if (std::max({dot_i, dot_j, dot_k}) > sliver_cotangent * double_area) {
      ++degenerate;
      sums.at_sliver[i] = sums.at_sliver[j] = sums.at_sliver[k] = 1;
      continue;
    }

    // Mixed Voronoi area (Meyer et al. 2002, Fig. 4).
    const double area = 0.5 * double_area;
    const double cot_i = dot_i / double_area, cot_j = dot_j / double_area,
                 cot_k = dot_k / double_area;
    if (dot_i < 0.0) {
      sums.area[i] += 0.5 * area;
      sums.area[j] += 0.25 * area;
      sums.area[k] += 0.25 * area;
    } else if (dot_j < 0.0) {
      sums.area[i] += 0.25 * area;
      sums.area[j] += 0.5 * area;
      sums.area[k] += 0.25 * area;
    } else if (dot_k < 0.0) {
      sums.area[i] += 0.25 * area;
      sums.area[j] += 0.25 * area;
      sums.area[k] += 0.5 * area;
    } else {
      sums.area[i] += 0.125 * (ab2 * cot_k + ca2 * cot_j);
      sums.area[j] += 0.125 * (bc2 * cot_i + ab2 * cot_k);
      sums.area[k] += 0.125 * (ca2 * cot_j + bc2 * cot_i);
    }

    // Cotangent Laplacian: the edge opposite each corner is weighted by that corner's cotangent.
    sums.laplacian[i] += cot_k * (-ab) + cot_j * ca;
    sums.laplacian[j] += cot_k * ab + cot_i * (-bc);
    sums.laplacian[k] += cot_i * bc + cot_j * (-ca);
  }
  return degenerate;
}

void set_principal(CurvatureField& field, std::size_t v) {
  const double root = std::sqrt(std::max(field.mean[v] * field.mean[v] - field.gaussian[v], 0.0));
  field.k1[v] = field.mean[v] + root;
  field.k2[v] = field.mean[v] - root;
}

void set_undefined(CurvatureField& field, std::size_t v) {
  field.gaussian[v] = field.mean[v] = field.k1[v] = field.k2[v] = 0.0;
  field.status[v] = CurvatureStatus::undefined;
}

// Boundary and non-manifold vertices take the mean of their computed neighbours.
void extrapolate(const TriangleMesh& mesh, const VertexFaces& vf, CurvatureField& field) {
  for (std::size_t v = 0; v < field.status.size(); ++v) {
    if (field.status[v] != CurvatureStatus::extrapolated) continue;
    double gaussian = 0.0, mean = 0.0;
    int count = 0;
    for (std::int32_t f : vf.of(static_cast<std::int32_t>(v))) {
      for (std::int32_t w : mesh.triangles[f]) {
        // Neighbours appear in two faces each; counting them twice keeps the mean unchanged.
        if (static_cast<std::size_t>(w) == v || field.status[w] != CurvatureStatus::computed)
          continue;
        gaussian += field.gaussian[w];
        mean += field.mean[w];
        ++count;
      }
    }
    if (count == 0) {
      set_undefined(field, v);
      continue;
    }
    field.gaussian[v] = gaussian / count;
    field.mean[v] = mean / count;
    set_principal(field, v);
  }
}

}  // namespace

CurvatureField compute_curvature(const TriangleMesh& mesh, const MeshTopology& topology) {
  const std::size_t n = mesh.positions.size();
  const double scale = power_of_two_scale(mesh.positions);

  // One pass over the faces; each worker sums into its own arrays, merged afterwards.
  const std::size_t workers = worker_count(mesh.triangles.size());
  std::vector<FaceSums> sums;
  sums.reserve(workers);
  for (std::size_t w = 0; w < workers; ++w) sums.emplace_back(n);
  std::vector<std::size_t> degenerate(workers, 0);
  parallel_chunks(mesh.triangles.size(), workers,
                  [&](std::size_t w, std::size_t begin, std::size_t end) {
                    degenerate[w] = accumulate_faces(mesh, scale, begin, end, sums[w]);
                  });

  CurvatureField field;
  field.normal.resize(n);
  field.gaussian.resize(n);
  field.mean.resize(n);
  field.k1.resize(n);
  field.k2.resize(n);
  field.status.resize(n);
  for (std::size_t d : degenerate) field.sliver_faces += d;

  const double scale2 = scale * scale;
  FaceSums& total = sums[0];
  parallel_chunks(n, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      for (std::size_t w = 1; w < workers; ++w) {
        total.area[v] += sums[w].area[v];
        total.angle[v] += sums[w].angle[v];
        total.laplacian[v] += sums[w].laplacian[v];
        total.normal[v] += sums[w].normal[v];
        total.at_sliver[v] |= sums[w].at_sliver[v];
      }
      const double area = total.area[v];
      const double normal_length = total.normal[v].norm();
      field.normal[v] = normal_length > 0.0 ? Vec3(total.normal[v] / normal_length) : Vec3::Zero();
      if (area <= 0.0 || normal_length == 0.0 || topology.kind[v] == VertexKind::isolated) {
        set_undefined(field, v);
        continue;
      }
      if (topology.kind[v] != VertexKind::interior || total.at_sliver[v]) {
        field.status[v] = CurvatureStatus::extrapolated;
        continue;
      }
      // In scaled units, then back: K ∝ 1/s², H ∝ 1/s.
      const double gaussian = (2.0 * std::numbers::pi - total.angle[v]) / area * scale2;
      const double mean = total.laplacian[v].dot(field.normal[v]) / (4.0 * area) * scale;
      if (!std::isfinite(gaussian) || !std::isfinite(mean)) {
        set_undefined(field, v);
        continue;
      }
      field.gaussian[v] = gaussian;
      field.mean[v] = mean;
      field.status[v] = CurvatureStatus::computed;
      set_principal(field, v);
    }
  });
  extrapolate(mesh, topology.vertex_faces, field);

  field.area = std::move(total.area);
  for (double& a : field.area) a = std::isfinite(a / scale2) ? a / scale2 : 0.0;
  field.undefined_vertices = static_cast<std::size_t>(
      std::count(field.status.begin(), field.status.end(), CurvatureStatus::undefined));
  field.extrapolated_vertices = static_cast<std::size_t>(
      std::count(field.status.begin(), field.status.end(), CurvatureStatus::extrapolated));
  return field;
}

}  // namespace toonwater
