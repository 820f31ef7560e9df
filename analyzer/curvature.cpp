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
#include "analyzer/vertex_normals.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace toonwater {
namespace {

constexpr double sliver_cotangent = 19.08113668772821;  // cot(3°)

// 2^-e with e the binary exponent of the largest |coordinate|: multiplying by it is exact.
double power_of_two_scale(const std::vector<Vec3>& positions) {
  double largest = 0.0;
  for (const Vec3& p : positions) largest = std::max(largest, p.cwiseAbs().maxCoeff());
  if (largest == 0.0 || !std::isfinite(largest)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(largest));
}

// What one vertex gathers from its incident faces.
struct OneRing {
  double area = 0.0;
  double angle_deficit = 0.0;   // 2π − Σθ
  Vec3 laplacian = Vec3::Zero();  // Σ (cot α + cot β)(xᵢ − xⱼ)
  Vec3 normal = Vec3::Zero();     // Σ θ n_face
  bool at_sliver = false;        // a corner of a sliver face
  std::size_t slivers = 0;       // faces counted here: those whose first corner this vertex is
};

// The angle sum Σθ is accumulated as the argument of the product of the unit complex numbers
// (cos θ + i sin θ) = (u·v + i|u×v|)/(|u||v|), counting the turns as the product crosses the
// negative real axis (each θ ≤ π, so a crossing shows as Im going from ≥ 0 to < 0). The deficit
// of a nearly flat vertex is then the small argument itself, not the difference of two numbers
// near 2π, and it costs one atan2 per vertex instead of one per corner.
OneRing gather_one_ring(const TriangleMesh& mesh, const VertexFaces& vf, double scale,
                        std::int32_t v) {
  OneRing ring;
  double turn_re = 1.0, turn_im = 0.0;  // the running product, kept at unit length
  int turns = 0;
  const Vec3 x = mesh.positions[v] * scale;
  for (std::int32_t f : vf.of(v)) {
    const Triangle& t = mesh.triangles[f];
    const int corner = t[0] == v ? 0 : t[1] == v ? 1 : 2;
    const Vec3 a = mesh.positions[t[(corner + 1) % 3]] * scale;
    const Vec3 b = mesh.positions[t[(corner + 2) % 3]] * scale;
    const Vec3 xa = a - x, xb = b - x, ab = b - a;
    const double xa2 = xa.squaredNorm(), xb2 = xb.squaredNorm(), ab2 = ab.squaredNorm();
    const bool counts_here = corner == 0;
    if (xa2 == 0.0 || xb2 == 0.0 || ab2 == 0.0) {  // a face with a zero-length edge: no shape
      ring.slivers += counts_here;
      continue;
    }
    const Vec3 cross = xa.cross(xb);
    const double double_area = cross.norm();
    const double dot_x = xa.dot(xb);     // at this vertex
    const double dot_a = -xa.dot(ab);    // at a: between a→x and a→b
    const double dot_b = xb.dot(ab);     // at b: between b→x and b→a

    // Written out: std::complex's operator* and abs guard against inf/NaN at several times the cost.
    const double inverse_length = 1.0 / std::sqrt(xa2 * xb2);  // 1 / (|xa| |xb|)
    const double c = dot_x * inverse_length, s = double_area * inverse_length;
    const double next_re = turn_re * c - turn_im * s, next_im = turn_re * s + turn_im * c;
    turns += turn_im >= 0.0 && next_im < 0.0;
    turn_re = next_re;
    turn_im = next_im;

    const double longest2 = std::max({xa2, xb2, ab2});
    ring.normal += corner_normal_term(cross, double_area, dot_x, longest2);
    const bool sliver = double_area <= degenerate_area_ratio * longest2 ||
                        std::max({dot_x, dot_a, dot_b}) > sliver_cotangent * double_area;
    if (sliver) {
      ring.at_sliver = true;
      ring.slivers += counts_here;
      continue;
    }

    // Mixed Voronoi area (Meyer et al. 2002, Fig. 4).
    const double face_area = 0.5 * double_area;
    const double inverse_area = 1.0 / double_area;
    const double cot_a = dot_a * inverse_area, cot_b = dot_b * inverse_area;
    if (dot_x < 0.0)
      ring.area += 0.5 * face_area;
    else if (dot_a < 0.0 || dot_b < 0.0)
      ring.area += 0.25 * face_area;
    else
      ring.area += 0.125 * (xa2 * cot_b + xb2 * cot_a);

    // Cotangent Laplacian: edge x–a is weighted by the cotangent at b, edge x–b by that at a.
    ring.laplacian -= cot_b * xa + cot_a * xb;
  }
  ring.angle_deficit = -(std::atan2(turn_im, turn_re) + 2.0 * std::numbers::pi * (turns - 1));
  return ring;
}

void set_undefined(CurvatureField& field, std::size_t v) {
  set_curvature(field, v, 0.0, 0.0);
  field.status[v] = CurvatureStatus::undefined;
}

}  // namespace

void set_curvature(CurvatureField& field, std::size_t v, double gaussian, double mean) {
  field.gaussian[v] = gaussian;
  field.mean[v] = mean;
  const double root = std::sqrt(std::max(mean * mean - gaussian, 0.0));
  field.k1[v] = mean + root;
  field.k2[v] = mean - root;
}

void extrapolate_from_neighbours(const TriangleMesh& mesh, const VertexFaces& vf,
                                 CurvatureField& field) {
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
    if (count == 0)
      set_undefined(field, v);
    else
      set_curvature(field, v, gaussian / count, mean / count);
  }
  field.undefined_vertices = static_cast<std::size_t>(
      std::count(field.status.begin(), field.status.end(), CurvatureStatus::undefined));
  field.extrapolated_vertices = static_cast<std::size_t>(
      std::count(field.status.begin(), field.status.end(), CurvatureStatus::extrapolated));
}

CurvatureField compute_curvature(const TriangleMesh& mesh, const MeshTopology& topology) {
  const std::size_t n = mesh.positions.size();
  const double scale = power_of_two_scale(mesh.positions);
  const double scale2 = scale * scale;

  CurvatureField field;
  field.normal.resize(n);
  field.area.resize(n);
  field.gaussian.resize(n);
  field.mean.resize(n);
  field.k1.resize(n);
  field.k2.resize(n);
  field.status.resize(n);

  // Each vertex gathers from its own faces (compressed rows, no halfedges), so the vertices
  // split over the cores with no shared writes.
  const std::size_t workers = worker_count(n);
  std::vector<std::size_t> slivers(workers, 0);
  parallel_chunks(n, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
    for (std::size_t v = begin; v < end; ++v) {
      const OneRing ring =
          gather_one_ring(mesh, topology.vertex_faces, scale, static_cast<std::int32_t>(v));
      slivers[worker] += ring.slivers;
      const double normal_length = ring.normal.norm();
      field.normal[v] = normal_length > 0.0 ? Vec3(ring.normal / normal_length) : Vec3::Zero();
      const double area = ring.area / scale2;
      field.area[v] = std::isfinite(area) ? area : 0.0;
      if (ring.area <= 0.0 || normal_length == 0.0 || topology.kind[v] == VertexKind::isolated) {
        set_undefined(field, v);
        continue;
      }
      if (topology.kind[v] != VertexKind::interior || ring.at_sliver) {
        field.status[v] = CurvatureStatus::extrapolated;
        continue;
      }
      // In scaled units, then back: K ∝ 1/s², H ∝ 1/s.
      const double gaussian = ring.angle_deficit / ring.area * scale2;
      const double mean = ring.laplacian.dot(field.normal[v]) / (4.0 * ring.area) * scale;
      if (!std::isfinite(gaussian) || !std::isfinite(mean)) {
        set_undefined(field, v);
        continue;
      }
      set_curvature(field, v, gaussian, mean);
      field.status[v] = CurvatureStatus::computed;
    }
  });
  for (std::size_t count : slivers) field.sliver_faces += count;
  for (const Triangle& t : mesh.triangles) field.sliver_faces += has_repeated_corner(t);
  extrapolate_from_neighbours(mesh, topology.vertex_faces, field);
  return field;
}

}  // namespace toonwater
