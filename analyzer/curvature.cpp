// Discrete curvature after Meyer, Desbrun, Schröder and Barr (2002); formulas in curvature.hpp.
//
// Robustness choices (each guards against a way common curvature code fails on real meshes):
// - Positions are scaled by a power of two so that the largest coordinate is of order one. The
//   scaling is exact, so K ∝ 1/s² and H ∝ 1/s hold to the last bit for power-of-two scales, and
//   coordinates near 1e±300 neither overflow nor underflow in the squared lengths.
// - Angles come from atan2(|u×v|, u·v), cotangents from (u·v)/|u×v| — never acos. An angle is
//   well conditioned at any shape (atan2 of two accurate numbers), so every face gives its
//   corner angles, and the angle deficits sum to 2πχ on a closed mesh (Gauss–Bonnet), exactly
//   up to round-off.
// - Thin faces are kept as they are. A UV sphere's pole fans (2.5° at 10k vertices) or a
//   stretched quad are exact geometry, and their cotangents (u·v)/|u×v| are accurate: |u×v| has
//   a relative round-off error of about ε/sin θ, 1e-14 at 0.06°.
// - Where a face has an angle above 150°, or is within ε = 1e-6 of violating the triangle
//   inequality, the cotangent weights of the Laplacian come from the intrinsic Delaunay
//   triangulation (intrinsic_delaunay.hpp: Fisher, Springborn, Bobenko, Schröder 2007) of the
//   mesh's edge lengths, each first increased by the least δ that gives every face a slack
//   ℓᵢ + ℓⱼ − ℓₖ ≥ ε ℓₖ (intrinsic mollification, Sharp and Crane 2020). Such a face is where
//   the cotangent operator stops describing the surface: a cap standing on edge — a T-junction
//   as marching cubes leaves them, its third vertex a hair off the long edge — makes the
//   cotangent Laplacian see a 90° crease along that edge (MeshLab returns H = 1e7 next to one),
//   and a collinear face has no cotangents at all. Flipping the edges whose cotangent weight is
//   negative removes both. The Laplacian still acts on the positions; angles (so the deficit)
//   and the mixed areas stay the mesh's own, exact geometry, so K and the area a vertex stands
//   for do not depend on the triangulation chosen for L. A mesh without such faces (every
//   analytic test surface) is computed from its positions alone, in one pass; the first pass
//   detects the need for the second.
//   Measured against the alternatives (README, "Thin and degenerate faces"):
//   · leaving thin faces out (angles below 3°, as this code did): the UV sphere's poles become
//     undefined or extrapolated, error 0.17 at 10k vertices against MeshLab's 5.7e-3;
//   · clamping cotangents at cot 3° (pmp-library): changes exact pole fans (UV sphere 10k:
//     K error 6.9e-3, H 4.5e-3, 16× and 33× the unclamped operator) and leaves the crease of
//     a standing cap (H off by 11 at its corners);
//   · mollification alone: exact on the UV sphere, but the cap's crease stays (H off by 11);
//   · mollification and intrinsic Delaunay for the Laplacian (chosen): exact on the UV sphere,
//     no crease (H within 0.34 of the sphere's at the cap's corners). Taking the intrinsic
//     triangulation's Voronoi areas as well made K 2.7× worse on a jittered UV sphere (its
//     sheared pole fans) and H at the cap twice as far off, so the areas stay the mesh's.
// - A face with a repeated corner or a zero-length edge has no shape (no angles, no plane) and
//   contributes nothing; its corners lack part of their one-ring.
// - Boundary and non-manifold vertices and the corners of shapeless faces have no complete
//   one-ring: at a boundary the angle deficit measures the geodesic curvature of the boundary
//   (π − Σθ), not a property of the surface. Their K and H are the mean of their computed
//   neighbours' values (status `extrapolated`), so a map of an open sheet has no spurious rim.
// - H takes the length of the mean curvature normal L = Σ (cot α + cot β)(xᵢ − xⱼ), as Meyer et
//   al. define it (and MeshLab computes it), not only its projection on n̂: on a regular wave
//   field of 10k vertices the projection's error is 0.13% larger. Where L leans more than 10°
//   from n̂ (near H = 0, or on irregular meshes, where its tangential part is discretisation
//   error) H is the projection divided by cos 10°: the length alone would jump from +|L| to
//   −|L| as L·n̂ changes sign, and a rotation's round-off would flip it.
// - A vertex with no area or no usable normal, or whose values are not finite, gets zeros
//   (status `undefined`) and is counted.
#include "analyzer/curvature.hpp"

#include "analyzer/geometry_tolerances.hpp"
#include "analyzer/intrinsic_delaunay.hpp"
#include "common/parallel.hpp"
#include "analyzer/vertex_normals.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <span>
#include <stdexcept>

namespace toonwater {
namespace {

// ε of the mollification: the least triangle-inequality slack, relative to a face's longest edge.
constexpr double mollification_slack = 1e-6;
// Slack ≥ h²/ℓₖ for a face of height h over its longest edge ℓₖ, so a face whose doubled area
// h ℓₖ is at least sqrt(ε) ℓₖ² has slack ≥ ε ℓₖ and needs no check of its lengths.
constexpr double mollification_area_ratio = 1e-3;  // sqrt(mollification_slack)
static_assert(mollification_area_ratio * mollification_area_ratio >= mollification_slack);

// A face with an angle above 150° (cot < −√3) makes the mesh take the intrinsic Delaunay
// triangulation: an edge opposite such an angle has a negative cotangent weight unless the
// angle across it is below 30°.
constexpr double cap_cotangent = -1.7320508075688772;  // cot(150°)

// H is half the length of the mean curvature normal L/(2A) while L is within 10° of n̂, with the
// sign of L·n̂; beyond, L·n̂ / cos 10°, so that H is continuous where L turns tangential.
constexpr double normal_deviation_secant = 1.0154266118857451;  // 1 / cos(10°)

// 2^-e with e the binary exponent of the largest |coordinate|: multiplying by it is exact.
double power_of_two_scale(const std::vector<Vec3>& positions) {
  const std::size_t workers = worker_count(positions.size());
  std::vector<double> largest_of(workers, 0.0);
  parallel_chunks(positions.size(), workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
    double largest = 0.0;
    for (std::size_t v = begin; v < end; ++v) largest = std::max(largest, positions[v].cwiseAbs().maxCoeff());
    largest_of[worker] = largest;
  });
  const double largest = *std::max_element(largest_of.begin(), largest_of.end());
  if (largest == 0.0 || !std::isfinite(largest)) return 1.0;
  return std::ldexp(1.0, -std::ilogb(largest));
}

// The δ that face (x, a, b) needs (≤ 0: none), from its squared edge lengths.
double mollification_needed(double xa2, double xb2, double ab2) {
  const double la = std::sqrt(xa2), lb = std::sqrt(xb2), lab = std::sqrt(ab2);
  const double longest = std::max({la, lb, lab});
  const double slack = la + lb + lab - 2.0 * longest;
  // slack + δ ≥ ε (longest + δ)
  return (mollification_slack * longest - slack) / (1.0 - mollification_slack);
}

// 2^-e for the binary exponent e of m ≥ 0, from its exponent bits alone (a few integer
// operations, where std::ilogb and std::ldexp are calls), so that m · 2^-e lies in [1, 2). Kept
// finite at the ends: subnormals take e = −1023, and m ≥ 2^1023, inf and NaN take e = 1022.
double power_of_two_below(double m) {
  const std::uint64_t biased = std::min<std::uint64_t>((std::bit_cast<std::uint64_t>(m) >> 52) & 0x7ff, 2045);
  return std::bit_cast<double>((2046 - biased) << 52);
}

// Whether re + i·im lies in [π, 2π) (see add_corner).
bool in_lower_half(double re, double im) { return im < 0.0 || (im == 0.0 && re < 0.0); }

// One face's contributions to each of its corners, computed once for the three. Corner i's
// neighbours are i + 1 and i + 2 (mod 3); edge[i] runs from corner i to corner i + 1.
struct FaceTerms {
  bool shapeless;         // a zero-length edge: no shape, no contributions
  double double_area;     // |u × v|
  double dot[3];          // u · v at each corner
  Vec3 normal[3];         // θ n_face at each corner (vertex_normals.hpp)
  double area[3];         // the corner's share of the mixed Voronoi area
  Vec3 laplacian[3];      // the corner's Laplacian terms, from the positions
  double mollification;   // the δ the face needs (≤ 0: none)
  bool cap;               // an angle above 150°
};

// The face's terms from its scaled positions. Every corner takes the same cross product
// u × v = edge[2] × edge[0] and the same reciprocal of its length, so the corners of one face
// agree to the last bit on its plane and area.
[[gnu::always_inline]] inline FaceTerms face_terms(const std::vector<Vec3>& positions,
                                                   const Triangle& t, double scale) {
  FaceTerms face;
  // Written out in coordinates: kept in registers, where the compiler would store Eigen's
  // three-element vectors in halves and reload them whole.
  const Vec3& q0 = positions[t[0]];
  const Vec3& q1 = positions[t[1]];
  const Vec3& q2 = positions[t[2]];
  const double p0[3] = {q0.x() * scale, q0.y() * scale, q0.z() * scale};
  const double p1[3] = {q1.x() * scale, q1.y() * scale, q1.z() * scale};
  const double p2[3] = {q2.x() * scale, q2.y() * scale, q2.z() * scale};
  double edge[3][3];
  for (int k = 0; k < 3; ++k) {
    edge[0][k] = p1[k] - p0[k];
    edge[1][k] = p2[k] - p1[k];
    edge[2][k] = p0[k] - p2[k];
  }
  auto dot = [](const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const double length2[3] = {dot(edge[0], edge[0]), dot(edge[1], edge[1]), dot(edge[2], edge[2])};
  face.shapeless = is_shapeless_triangle(length2[0], length2[1], length2[2]);
  if (face.shapeless) return face;
  const Vec3 cross(edge[2][1] * edge[0][2] - edge[2][2] * edge[0][1],
                   edge[2][2] * edge[0][0] - edge[2][0] * edge[0][2],
                   edge[2][0] * edge[0][1] - edge[2][1] * edge[0][0]);
  const double double_area =
      std::sqrt(cross.x() * cross.x() + cross.y() * cross.y() + cross.z() * cross.z());
  face.double_area = double_area;
  // At corner i, u = edge[i] and v = −edge[i + 2].
  face.dot[0] = -dot(edge[0], edge[2]);
  face.dot[1] = -dot(edge[1], edge[0]);
  face.dot[2] = -dot(edge[2], edge[1]);
  const double longest2 = std::max({length2[0], length2[1], length2[2]});
  for (int i = 0; i < 3; ++i)
    face.normal[i] = corner_normal_term(cross, double_area, face.dot[i], longest2);
  face.mollification = double_area >= mollification_area_ratio * longest2
                           ? 0.0
                           : mollification_needed(length2[0], length2[2], length2[1]);
  face.cap = std::min({face.dot[0], face.dot[1], face.dot[2]}) < cap_cotangent * double_area;
  // Mixed Voronoi area (Meyer et al. 2002, Fig. 4), always the mesh's own.
  const double inverse_area = 1.0 / double_area;
  const double cot[3] = {face.dot[0] * inverse_area, face.dot[1] * inverse_area,
                         face.dot[2] * inverse_area};
  const bool obtuse = face.dot[0] < 0.0 || face.dot[1] < 0.0 || face.dot[2] < 0.0;
  for (int i = 0; i < 3; ++i) {
    const int next = i == 2 ? 0 : i + 1, last = i == 0 ? 2 : i - 1;
    if (face.dot[i] < 0.0)
      face.area[i] = 0.25 * double_area;
    else if (obtuse)
      face.area[i] = 0.125 * double_area;
    else
      face.area[i] = 0.125 * (length2[i] * cot[last] + length2[last] * cot[next]);
    // Cotangent Laplacian: edge i → next is weighted by the cotangent at last, edge i → last
    // by that at next.
    face.laplacian[i] = Vec3(cot[next] * edge[last][0] - cot[last] * edge[i][0],
                             cot[next] * edge[last][1] - cot[last] * edge[i][1],
                             cot[next] * edge[last][2] - cot[last] * edge[i][2]);
  }
  return face;
}

// What one vertex sums over its faces, but for its normal and area, which are summed in place
// in the field's arrays.
struct RingSums {
  Vec3 laplacian;     // Σ (cot α + cot β)(xᵢ − xⱼ)
  double turn_re;     // the running product of the corners' u·v + i|u×v|
  double turn_im;
  std::int32_t turns;
  bool at_shapeless;  // a corner of a face with a zero-length edge
};

void start_ring(RingSums& sums, Vec3& normal, double& area) {
  sums.laplacian = Vec3::Zero();
  sums.turn_re = 1.0;
  sums.turn_im = 0.0;
  sums.turns = 0;
  sums.at_shapeless = false;
  normal = Vec3::Zero();
  area = 0.0;
}

// The angle sum Σθ is accumulated as the argument of the product of the complex numbers
// u·v + i|u×v| = |u||v| (cos θ + i sin θ), counting the turns as the product enters the
// lower half-plane [π, 2π) — Im < 0, or Im = 0 with Re < 0, so that the exact angles of π/2 and π
// of a grid and a collinear face, which leave Im at ±0, count too (each θ ≤ π, so a step can
// cross π at most once). The deficit of a nearly flat vertex is then the small argument itself,
// not the difference of two numbers near 2π, and it costs one atan2 per vertex instead of one
// per corner. The product is not normalised by |u||v| (a square root and a division per
// corner) but brought back to a magnitude in [1, 2) after each step by a power of two, which is
// exact: the argument is that of the unit product up to round-off.
[[gnu::always_inline]] inline void add_corner(const FaceTerms& face, int corner, bool laplacian,
                                              RingSums& sums, Vec3& normal, double& area) {
  if (face.shapeless) {
    sums.at_shapeless = true;
    return;
  }
  // Written out: std::complex's operator* and abs guard against inf/NaN at several times the cost.
  const double dot = face.dot[corner], double_area = face.double_area;
  const double next_re = sums.turn_re * dot - sums.turn_im * double_area;
  const double next_im = sums.turn_re * double_area + sums.turn_im * dot;
  sums.turns += !in_lower_half(sums.turn_re, sums.turn_im) && in_lower_half(next_re, next_im);
  const double normaliser = power_of_two_below(std::max(std::abs(next_re), std::abs(next_im)));
  sums.turn_re = next_re * normaliser;
  sums.turn_im = next_im * normaliser;
  normal += face.normal[corner];
  area += face.area[corner];
  if (laplacian) sums.laplacian += face.laplacian[corner];
}

// The Laplacian terms of corner x of a face (x, a, b) with edge lengths |xa| = la, |xb| = lb,
// |ab| = lab; xa = a − x and xb = b − x are positions.
void add_laplacian_terms(Vec3& laplacian, double la, double lb, double lab, const Vec3& xa,
                         const Vec3& xb) {
  const double la2 = la * la, lb2 = lb * lb, lab2 = lab * lab;
  const double inverse_area = 0.5 / double_area_from_lengths(la, lb, lab);  // cot = (…)/(4A)
  const double cot_a = (la2 + lab2 - lb2) * inverse_area;
  const double cot_b = (lb2 + lab2 - la2) * inverse_area;
  laplacian -= cot_b * xa + cot_a * xb;
}

int corner_of(const Triangle& t, std::int32_t v) { return t[0] == v ? 0 : t[1] == v ? 1 : 2; }

void set_undefined(CurvatureField& field, std::size_t v) {
  set_curvature(field, v, 0.0, 0.0);
  field.status[v] = CurvatureStatus::undefined;
}

struct GatherInput {
  const TriangleMesh& mesh;
  const MeshTopology& topology;
  double scale;
  // Without it, the Laplacian's cotangents come from the faces' positions; with it, from its
  // faces and lengths. Angles, normal and area always come from the mesh's own faces.
  const IntrinsicTriangulation* intrinsic;
  // The face chunks of the face pass: chunk c is [face_bounds[c], face_bounds[c + 1]).
  std::span<const std::size_t> face_bounds;
  RingSums* sums;  // per vertex
};

struct GatherCounts {
  std::size_t shapeless = 0, mollified = 0, caps = 0;
  double mollification = 0.0;
};

// Whether all of v's faces lie in one face chunk: the face pass then sums v's terms in the
// order of its faces, which is the order of its row (build_vertex_faces fills each row in
// ascending face order). Otherwise v is summed by the vertex pass, from its row, in that same
// order: either way the same sums, whatever the number of chunks.
bool in_one_chunk(std::span<const std::int32_t> row, std::span<const std::size_t> face_bounds) {
  const auto first = static_cast<std::size_t>(row.front()), last = static_cast<std::size_t>(row.back());
  for (std::size_t c = 1; c + 1 < face_bounds.size(); ++c)
    if (first < face_bounds[c] && face_bounds[c] <= last) return false;
  return true;
}

// The face pass over faces [begin, end): each face's terms are computed once and added to the
// sums of those of its corners whose faces all lie in [begin, end). The first face of a vertex
// starts its sums, so no array needs clearing beforehand. Forced inline so that each of the two
// instantiations below compiles all of it for its own instruction set.
[[gnu::always_inline]] inline void sum_faces(const GatherInput& in, std::size_t begin,
                                             std::size_t end, CurvatureField& field,
                                             GatherCounts& counts) {
  const VertexFaces& vf = in.topology.vertex_faces;
  const std::vector<Triangle>& triangles = in.mesh.triangles;
  const bool laplacian = in.intrinsic == nullptr;
  for (std::size_t f = begin; f < end; ++f) {
    const Triangle& t = triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // in no row (topology.hpp)
    const FaceTerms face = face_terms(in.mesh.positions, t, in.scale);
    if (face.shapeless) {
      ++counts.shapeless;
    } else {
      if (face.mollification > 0.0) {
        ++counts.mollified;
        counts.mollification = std::max(counts.mollification, face.mollification);
      }
      counts.caps += face.cap;
    }
    for (int corner = 0; corner < 3; ++corner) {
      const std::int32_t v = t[corner];
      const std::int32_t first = vf.face_indices[vf.offsets[v]];
      const std::int32_t last = vf.face_indices[vf.offsets[v + 1] - 1];
      if (static_cast<std::size_t>(first) < begin || static_cast<std::size_t>(last) >= end) continue;
      if (static_cast<std::size_t>(first) == f) start_ring(in.sums[v], field.normal[v], field.area[v]);
      add_corner(face, corner, laplacian, in.sums[v], field.normal[v], field.area[v]);
    }
  }
}

// The vertex pass over vertices [begin, end): sums the vertices the face pass left out, then
// turns every vertex's sums into its fields.
[[gnu::always_inline]] inline void finish_vertices(const GatherInput& in, std::size_t begin,
                                                   std::size_t end, CurvatureField& field) {
  const VertexFaces& vf = in.topology.vertex_faces;
  const double scale = in.scale, scale2 = scale * scale;
  for (std::size_t v = begin; v < end; ++v) {
    const auto vertex = static_cast<std::int32_t>(v);
    const std::span<const std::int32_t> row = vf.of(vertex);
    RingSums& sums = in.sums[v];
    if (row.empty()) {
      start_ring(sums, field.normal[v], field.area[v]);
    } else if (!in_one_chunk(row, in.face_bounds)) {
      start_ring(sums, field.normal[v], field.area[v]);
      for (std::int32_t f : row) {
        const Triangle& t = in.mesh.triangles[f];
        add_corner(face_terms(in.mesh.positions, t, scale), corner_of(t, vertex),
                   in.intrinsic == nullptr, sums, field.normal[v], field.area[v]);
      }
    }
    if (in.intrinsic) {
      const Vec3 x = in.mesh.positions[v] * scale;
      for (std::int32_t f : in.intrinsic->vertex_faces.of(vertex)) {
        const Triangle& t = in.intrinsic->faces[f];
        const auto& l = in.intrinsic->lengths[f];
        const int corner = corner_of(t, vertex);
        const int next = (corner + 1) % 3, last = (corner + 2) % 3;
        const Vec3 xa = in.mesh.positions[t[next]] * scale - x;
        const Vec3 xb = in.mesh.positions[t[last]] * scale - x;
        add_laplacian_terms(sums.laplacian, l[corner], l[last], l[next], xa, xb);
      }
    }
    const double ring_area = field.area[v];
    const Vec3 normal_sum = field.normal[v];
    const double normal_length = normal_sum.norm();
    field.normal[v] = normal_length > 0.0 ? Vec3(normal_sum / normal_length) : Vec3::Zero();
    const double area = ring_area / scale2;
    field.area[v] = std::isfinite(area) ? area : 0.0;
    const VertexKind kind = in.topology.kind[v];
    if (!(ring_area > 0.0) || normal_length == 0.0 || kind == VertexKind::isolated) {
      set_undefined(field, v);
      continue;
    }
    if (kind != VertexKind::interior || sums.at_shapeless) {
      field.status[v] = CurvatureStatus::extrapolated;
      continue;
    }
    // The argument in [−π, π), on the side of the branch cut that the turn count assumes.
    const double argument = in_lower_half(sums.turn_re, sums.turn_im)
                                ? -std::atan2(std::abs(sums.turn_im), sums.turn_re)
                                : std::atan2(std::abs(sums.turn_im), sums.turn_re);
    const double angle_deficit = -(argument + 2.0 * std::numbers::pi * (sums.turns - 1));
    // In scaled units, then back: K ∝ 1/s², H ∝ 1/s.
    const double gaussian = angle_deficit / ring_area * scale2;
    const double projected = sums.laplacian.dot(field.normal[v]);
    const double length = sums.laplacian.norm();
    const double laplacian_along_normal = length <= std::abs(projected) * normal_deviation_secant
                                              ? std::copysign(length, projected)
                                              : projected * normal_deviation_secant;
    const double mean = laplacian_along_normal / (4.0 * ring_area) * scale;
    if (!std::isfinite(gaussian) || !std::isfinite(mean)) {
      set_undefined(field, v);
      continue;
    }
    set_curvature(field, v, gaussian, mean);
    field.status[v] = CurvatureStatus::computed;
  }
}

// The same code for any x86-64 (SSE2) and for processors with AVX2 and FMA, chosen at run time:
// the portable build must not assume AVX2. This file is compiled with floating-point
// contraction allowed (analyzer/CMakeLists.txt), which on x86-64 only the second can use: there
// a·b + c becomes one fused multiply-add, rounded once. Its results differ from the portable
// path's by round-off only (tested); multiplying by the power-of-two scale stays exact, so the
// scale invariance holds in both. Elsewhere there is only the portable code.
void sum_faces_portable(const GatherInput& in, std::size_t begin, std::size_t end,
                        CurvatureField& field, GatherCounts& counts) {
  sum_faces(in, begin, end, field, counts);
}
void finish_vertices_portable(const GatherInput& in, std::size_t begin, std::size_t end,
                              CurvatureField& field) {
  finish_vertices(in, begin, end, field);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define TOONWATER_CURVATURE_AVX2_FMA 1
[[gnu::target("avx2,fma")]] void sum_faces_avx2_fma(const GatherInput& in, std::size_t begin,
                                                    std::size_t end, CurvatureField& field,
                                                    GatherCounts& counts) {
  sum_faces(in, begin, end, field, counts);
}
[[gnu::target("avx2,fma")]] void finish_vertices_avx2_fma(const GatherInput& in, std::size_t begin,
                                                          std::size_t end, CurvatureField& field) {
  finish_vertices(in, begin, end, field);
}
#endif

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

bool avx2_fma_supported() {
#ifdef TOONWATER_CURVATURE_AVX2_FMA
  static const bool supported = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return supported;
#else
  return false;
#endif
}

CurvatureField compute_curvature(const TriangleMesh& mesh, const MeshTopology& topology,
                                 CurvatureKernel kernel) {
  if (kernel == CurvatureKernel::avx2_fma && !avx2_fma_supported())
    throw std::invalid_argument("compute_curvature: this processor has no AVX2 and FMA");
  const std::size_t n = mesh.positions.size();
  const double scale = power_of_two_scale(mesh.positions);

  // The arrays are zero-filled as they are sized, and the filling (the first touch of every
  // page) costs about as much as a tenth of the gather: half of them on each of two cores.
  CurvatureField field;
  parallel_chunks(2, worker_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t half = begin; half < end; ++half) {
      if (half == 0) {
        field.normal.resize(n);
        field.area.resize(n);
        field.status.resize(n);
      } else {
        field.gaussian.resize(n);
        field.mean.resize(n);
        field.k1.resize(n);
        field.k2.resize(n);
      }
    }
  });

  // Each face's terms are computed once, in a pass over contiguous ranges of faces, one per
  // core; a vertex whose faces all lie in one range is summed there, the few others (faces on
  // both sides of a range's end) afterwards in the vertex pass, in the same order. The first
  // pass also finds the mollification the mesh needs; only a mesh that needs one is summed
  // again with it.
  const std::size_t workers = worker_count(n);
  const std::size_t m = mesh.triangles.size();
  std::vector<std::size_t> face_bounds(workers + 1);
  for (std::size_t c = 0; c <= workers; ++c) face_bounds[c] = m * c / workers;  // as parallel_chunks
  const auto sums = std::make_unique_for_overwrite<RingSums[]>(n);
  bool use_avx2_fma = false;
#ifdef TOONWATER_CURVATURE_AVX2_FMA
  use_avx2_fma = kernel == CurvatureKernel::avx2_fma ||
                 (kernel == CurvatureKernel::fastest && avx2_fma_supported());
#endif
  auto sum_all = [&](const IntrinsicTriangulation* intrinsic) {
    std::vector<GatherCounts> counts(workers);
    const GatherInput input{mesh, topology, scale, intrinsic, face_bounds, sums.get()};
    parallel_chunks(m, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
#ifdef TOONWATER_CURVATURE_AVX2_FMA
      if (use_avx2_fma) return sum_faces_avx2_fma(input, begin, end, field, counts[worker]);
#endif
      sum_faces_portable(input, begin, end, field, counts[worker]);
    });
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
#ifdef TOONWATER_CURVATURE_AVX2_FMA
      if (use_avx2_fma) return finish_vertices_avx2_fma(input, begin, end, field);
#endif
      finish_vertices_portable(input, begin, end, field);
    });
    GatherCounts total;
    for (const GatherCounts& c : counts) {
      total.shapeless += c.shapeless;
      total.mollified += c.mollified;
      total.caps += c.caps;
      total.mollification = std::max(total.mollification, c.mollification);
    }
    return total;
  };
  const GatherCounts counts = sum_all(nullptr);
  if (counts.mollification > 0.0 || counts.caps > 0) {
    const IntrinsicTriangulation intrinsic =
        intrinsic_delaunay(mesh, topology.vertex_faces, scale, std::max(counts.mollification, 0.0));
    field.intrinsic_flips = intrinsic.flips;
    sum_all(&intrinsic);
  }
  // The rows hold three entries for each face without a repeated corner, and none for the others.
  field.degenerate_faces =
      counts.shapeless + mesh.triangles.size() - topology.vertex_faces.face_indices.size() / 3;
  field.mollified_faces = counts.mollified;
  field.mollification = counts.mollification / scale;
  field.cap_faces = counts.caps;
  extrapolate_from_neighbours(mesh, topology.vertex_faces, field);
  return field;
}

}  // namespace toonwater
