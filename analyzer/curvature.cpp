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
#include <numbers>
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

// Whether re + i·im lies in [π, 2π) (see gather_one_ring).
bool in_lower_half(double re, double im) { return im < 0.0 || (im == 0.0 && re < 0.0); }

// What one vertex gathers from its incident faces.
struct OneRing {
  double area = 0.0;
  double angle_deficit = 0.0;   // 2π − Σθ
  Vec3 laplacian = Vec3::Zero();  // Σ (cot α + cot β)(xᵢ − xⱼ)
  Vec3 normal = Vec3::Zero();     // Σ θ n_face
  bool at_shapeless = false;      // a corner of a face with a zero-length edge
  std::size_t shapeless = 0;      // such faces counted here: those whose first corner v is
  std::size_t mollified = 0;      // faces counted here that need mollification
  double mollification = 0.0;     // the largest δ those faces need
  std::size_t caps = 0;           // faces counted here with an angle above 150°
};

// The Laplacian terms of corner x of a face (x, a, b) with edge lengths |xa| = la, |xb| = lb,
// |ab| = lab; xa = a − x and xb = b − x are positions.
void add_laplacian_terms(OneRing& ring, double la, double lb, double lab, const Vec3& xa,
                         const Vec3& xb) {
  const double la2 = la * la, lb2 = lb * lb, lab2 = lab * lab;
  const double inverse_area = 0.5 / double_area_from_lengths(la, lb, lab);  // cot = (…)/(4A)
  const double cot_a = (la2 + lab2 - lb2) * inverse_area;
  const double cot_b = (lb2 + lab2 - la2) * inverse_area;
  ring.laplacian -= cot_b * xa + cot_a * xb;
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
//
// Without `intrinsic`, the Laplacian's cotangents come from the faces' positions; with it, from
// its faces and lengths. Angles, normal and area always come from the mesh's own faces.
[[gnu::always_inline]] inline OneRing gather_one_ring(const TriangleMesh& mesh, const VertexFaces& vf, double scale,
                                                      const IntrinsicTriangulation* intrinsic,
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
    if (is_shapeless_triangle(xa2, xb2, ab2)) {  // a face with a zero-length edge: no shape
      ring.at_shapeless = true;
      ring.shapeless += counts_here;
      continue;
    }
    const Vec3 cross = xa.cross(xb);
    const double double_area = cross.norm();
    const double dot_x = xa.dot(xb);     // at this vertex
    const double dot_a = -xa.dot(ab);    // at a: between a→x and a→b
    const double dot_b = xb.dot(ab);     // at b: between b→x and b→a

    // Written out: std::complex's operator* and abs guard against inf/NaN at several times the cost.
    const double next_re = turn_re * dot_x - turn_im * double_area;
    const double next_im = turn_re * double_area + turn_im * dot_x;
    turns += !in_lower_half(turn_re, turn_im) && in_lower_half(next_re, next_im);
    const double normaliser = power_of_two_below(std::max(std::abs(next_re), std::abs(next_im)));
    turn_re = next_re * normaliser;
    turn_im = next_im * normaliser;

    const double longest2 = std::max({xa2, xb2, ab2});
    ring.normal += corner_normal_term(cross, double_area, dot_x, longest2);
    if (counts_here && !(double_area >= mollification_area_ratio * longest2)) {
      const double needed = mollification_needed(xa2, xb2, ab2);
      if (needed > 0.0) {
        ++ring.mollified;
        ring.mollification = std::max(ring.mollification, needed);
      }
    }

    if (counts_here && std::min({dot_x, dot_a, dot_b}) < cap_cotangent * double_area) ++ring.caps;
    // Mixed Voronoi area (Meyer et al. 2002, Fig. 4), always the mesh's own.
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
    if (!intrinsic) ring.laplacian -= cot_b * xa + cot_a * xb;
  }
  if (intrinsic) {
    for (std::int32_t f : intrinsic->vertex_faces.of(v)) {
      const Triangle& t = intrinsic->faces[f];
      const auto& l = intrinsic->lengths[f];
      const int corner = t[0] == v ? 0 : t[1] == v ? 1 : 2;
      const int next = (corner + 1) % 3, last = (corner + 2) % 3;
      const Vec3 xa = mesh.positions[t[next]] * scale - x, xb = mesh.positions[t[last]] * scale - x;
      add_laplacian_terms(ring, l[corner], l[last], l[next], xa, xb);
    }
  }
  // The argument in [−π, π), on the side of the branch cut that the turn count assumes.
  const double argument = in_lower_half(turn_re, turn_im) ? -std::atan2(std::abs(turn_im), turn_re)
                                                          : std::atan2(std::abs(turn_im), turn_re);
  ring.angle_deficit = -(argument + 2.0 * std::numbers::pi * (turns - 1));
  return ring;
}

void set_undefined(CurvatureField& field, std::size_t v) {
  set_curvature(field, v, 0.0, 0.0);
  field.status[v] = CurvatureStatus::undefined;
}

struct GatherInput {
  const TriangleMesh& mesh;
  const MeshTopology& topology;
  double scale;
  const IntrinsicTriangulation* intrinsic;
};

struct GatherCounts {
  std::size_t shapeless = 0, mollified = 0, caps = 0;
  double mollification = 0.0;
};

// Gathers vertices [begin, end) and writes their fields. Forced inline so that each of the two
// instantiations below compiles all of it, the gather included, for its own instruction set.
[[gnu::always_inline]] inline void gather_vertices(const GatherInput& in, std::size_t begin,
                                                   std::size_t end, CurvatureField& field,
                                                   GatherCounts& counts) {
  const double scale = in.scale, scale2 = scale * scale;
  for (std::size_t v = begin; v < end; ++v) {
    const OneRing ring = gather_one_ring(in.mesh, in.topology.vertex_faces, scale, in.intrinsic,
                                         static_cast<std::int32_t>(v));
    counts.shapeless += ring.shapeless;
    counts.mollified += ring.mollified;
    counts.caps += ring.caps;
    counts.mollification = std::max(counts.mollification, ring.mollification);
    const double normal_length = ring.normal.norm();
    field.normal[v] = normal_length > 0.0 ? Vec3(ring.normal / normal_length) : Vec3::Zero();
    const double area = ring.area / scale2;
    field.area[v] = std::isfinite(area) ? area : 0.0;
    const VertexKind kind = in.topology.kind[v];
    if (!(ring.area > 0.0) || normal_length == 0.0 || kind == VertexKind::isolated) {
      set_undefined(field, v);
      continue;
    }
    if (kind != VertexKind::interior || ring.at_shapeless) {
      field.status[v] = CurvatureStatus::extrapolated;
      continue;
    }
    // In scaled units, then back: K ∝ 1/s², H ∝ 1/s.
    const double gaussian = ring.angle_deficit / ring.area * scale2;
    const double projected = ring.laplacian.dot(field.normal[v]);
    const double length = ring.laplacian.norm();
    const double laplacian_along_normal = length <= std::abs(projected) * normal_deviation_secant
                                              ? std::copysign(length, projected)
                                              : projected * normal_deviation_secant;
    const double mean = laplacian_along_normal / (4.0 * ring.area) * scale;
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
// scale invariance holds in both.
void gather_vertices_portable(const GatherInput& in, std::size_t begin, std::size_t end,
                              CurvatureField& field, GatherCounts& counts) {
  gather_vertices(in, begin, end, field, counts);
}

#if defined(__x86_64__) && defined(__GNUC__)
[[gnu::target("avx2,fma")]] void gather_vertices_avx2_fma(const GatherInput& in, std::size_t begin,
                                                          std::size_t end, CurvatureField& field,
                                                          GatherCounts& counts) {
  gather_vertices(in, begin, end, field, counts);
}
#else
void gather_vertices_avx2_fma(const GatherInput& in, std::size_t begin, std::size_t end,
                              CurvatureField& field, GatherCounts& counts) {
  gather_vertices(in, begin, end, field, counts);
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
#if defined(__x86_64__) && defined(__GNUC__)
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

  // Each vertex gathers from its own faces (compressed rows, no halfedges), so the vertices
  // split over the cores with no shared writes. The first pass also finds the mollification
  // the mesh needs; only a mesh that needs one is gathered again with it.
  const std::size_t workers = worker_count(n);
  const bool use_avx2_fma = kernel == CurvatureKernel::avx2_fma ||
                            (kernel == CurvatureKernel::fastest && avx2_fma_supported());
  auto gather_all = [&](const IntrinsicTriangulation* intrinsic) {
    std::vector<GatherCounts> counts(workers);
    const GatherInput input{mesh, topology, scale, intrinsic};
    parallel_chunks(n, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
      if (use_avx2_fma)
        gather_vertices_avx2_fma(input, begin, end, field, counts[worker]);
      else
        gather_vertices_portable(input, begin, end, field, counts[worker]);
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
  const GatherCounts counts = gather_all(nullptr);
  if (counts.mollification > 0.0 || counts.caps > 0) {
    const IntrinsicTriangulation intrinsic =
        intrinsic_delaunay(mesh, topology.vertex_faces, scale, std::max(counts.mollification, 0.0));
    field.intrinsic_flips = intrinsic.flips;
    gather_all(&intrinsic);
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
