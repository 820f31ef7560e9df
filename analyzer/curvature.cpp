// Discrete curvature after Meyer, Desbrun, Schröder and Barr (2002); formulas in curvature.hpp.
//
// Robustness choices (each guards against a way common curvature code fails on real meshes):
// - Positions are scaled by a power of two so that the largest coordinate is of order one. The
//   scaling is exact, so K ∝ 1/s² and H ∝ 1/s hold to the last bit for power-of-two scales, and
//   coordinates near 1e±300 neither overflow nor underflow in the squared lengths.
// - Angles are the arguments of u·v + i|u×v| (their product, add_corner), cotangents
//   (u·v)/|u×v| — never acos. An angle is well conditioned at any shape (the argument of two
//   accurate numbers), so every face gives its corner angles, and the angle deficits sum to 2πχ
//   on a closed mesh (Gauss–Bonnet), exactly up to round-off.
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
//   Measured against the alternatives (docs/analyzer.md, "Curvature"):
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

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <numbers>
#include <span>

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
  // A maximum is exact in any order, so the threads' maxima may be combined as they come.
  const double largest = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, positions.size(), serial_below), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double running) {
        for (std::size_t v = range.begin(); v < range.end(); ++v)
          running = std::max(running, positions[v].cwiseAbs().maxCoeff());
        return running;
      },
      [](double a, double b) { return std::max(a, b); });
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
// finite at the ends: subnormals take e = −1023, and m ≥ 2^1022, inf and NaN take e = 1022.
double power_of_two_below(double m) {
  const double clamped = m < 0x1p1022 ? m : 0x1p1022;
  const std::uint64_t biased = (std::bit_cast<std::uint64_t>(clamped) >> 52) & 0x7ff;
  return std::bit_cast<double>((2046 - biased) << 52);
}

// What a face gives one of its corners.
struct CornerTerms {
  Vec3 laplacian;            // its terms of Σ (cot α + cot β)(xᵢ − xⱼ), from the positions
  double approximate_angle;  // θ̃; NaN at a shapeless face, which has no angles
  Vec3 normal;               // θ n_face (vertex_normals.hpp)
  double area;               // its share of the mixed Voronoi area
  // u·v + i|u×v| times the power of two that brings the larger of its parts into [1, 2)
  // (add_corner); 1 at a shapeless face.
  double turn_re, turn_im;
};

struct FaceTerms {
  CornerTerms corner[3];
  double double_area;  // |u × v|
  double length2[3];   // squared edge lengths
  double longest2;
  bool shapeless;  // a zero-length edge
  bool cap;        // an angle above 150°
};

// The terms of a face, computed once for its three corners from their scaled positions.
// Corner i's neighbours are i + 1 and i + 2 (mod 3); edge[i] runs from corner i to corner
// i + 1. Every corner takes the same cross product u × v = edge[2] × edge[0] and the same
// reciprocal of its length, so the corners of one face agree to the last bit on its plane and
// area.
FaceTerms face_terms(const Vec3 (&position)[3]) {
  FaceTerms face;
  const Vec3 edge[3] = {position[1] - position[0], position[2] - position[1],
                        position[0] - position[2]};
  for (int i = 0; i < 3; ++i) face.length2[i] = edge[i].squaredNorm();
  face.shapeless = is_shapeless_triangle(face.length2[0], face.length2[1], face.length2[2]);
  const Vec3 cross = edge[2].cross(edge[0]);
  face.double_area = cross.norm();
  // At corner i, u = edge[i] and v = −edge[i + 2].
  const double corner_dot[3] = {-edge[0].dot(edge[2]), -edge[1].dot(edge[0]),
                                -edge[2].dot(edge[1])};
  face.longest2 = std::max({face.length2[0], face.length2[1], face.length2[2]});
  const double inverse_area = 1.0 / face.double_area;
  face.cap =
      std::min({corner_dot[0], corner_dot[1], corner_dot[2]}) < cap_cotangent * face.double_area;
  const double cot[3] = {corner_dot[0] * inverse_area, corner_dot[1] * inverse_area,
                         corner_dot[2] * inverse_area};
  const bool obtuse = corner_dot[0] < 0.0 || corner_dot[1] < 0.0 || corner_dot[2] < 0.0;
  for (int c = 0; c < 3; ++c) {
    const int next = c == 2 ? 0 : c + 1, last = c == 0 ? 2 : c - 1;
    CornerTerms& corner = face.corner[c];
    corner.normal = corner_normal_term(cross, face.double_area, corner_dot[c], face.longest2);
    if (face.shapeless) {
      corner.laplacian = Vec3::Zero();
      corner.approximate_angle = std::numeric_limits<double>::quiet_NaN();
      corner.area = 0.0;
      corner.turn_re = 1.0;
      corner.turn_im = 0.0;
      continue;
    }
    // Cotangent Laplacian: edge c → next is weighted by the cotangent at last, edge c → last
    // by that at next.
    corner.laplacian = cot[next] * edge[last] - cot[last] * edge[c];
    corner.approximate_angle = approximate_angle(face.double_area, corner_dot[c]);
    // Mixed Voronoi area (Meyer et al. 2002, Fig. 4), always the mesh's own.
    if (corner_dot[c] < 0.0)
      corner.area = 0.25 * face.double_area;
    else if (obtuse)
      corner.area = 0.125 * face.double_area;
    else
      corner.area = 0.125 * (face.length2[c] * cot[last] + face.length2[last] * cot[next]);
    const double turn_scale =
        power_of_two_below(std::max(std::abs(corner_dot[c]), face.double_area));
    corner.turn_re = corner_dot[c] * turn_scale;
    corner.turn_im = face.double_area * turn_scale;
  }
  return face;
}

FaceTerms face_terms(const TriangleMesh& mesh, const Triangle& t, double scale) {
  const Vec3 position[3] = {mesh.positions[t[0]] * scale, mesh.positions[t[1]] * scale,
                            mesh.positions[t[2]] * scale};
  return face_terms(position);
}

// The δ that a face needs (≤ 0: none).
double face_mollification(const FaceTerms& face) {
  return face.double_area >= mollification_area_ratio * face.longest2
             ? 0.0
             : mollification_needed(face.length2[0], face.length2[2], face.length2[1]);
}

// What one vertex sums over its faces, but for its normal and area, which are summed in place
// in the field's arrays: Σ (cot α + cot β)(xᵢ − xⱼ), Σθ̃ (NaN once a corner of a shapeless
// face was added), and the running product of the turn factors.
struct RingSums {
  Vec3 laplacian;
  double approximate_angle;
};
struct TurnProduct {
  double re, im;
};

// atan2(im, re) of a vertex's turn product. Most vertices are nearly flat, their product close
// to the positive real axis, where atan x = x − x³/3 + x⁵/5 − x⁷/7 + x⁹/9 for x = im/re
// (|x| < 2^-7) leaves out less than x^11/11, 1e-22 of x: as accurate as std::atan2 for a few
// multiply-adds, where std::atan2 costs about 125 instructions.
double turn_argument(double re, double im) {
  constexpr double series_limit = 0x1p-7;
  if (re > 0.0 && std::abs(im) < series_limit * re) {
    const double x = im / re, x2 = x * x;
    return x + x * x2 * (-1.0 / 3 + x2 * (1.0 / 5 + x2 * (-1.0 / 7 + x2 * (1.0 / 9))));
  }
  return std::atan2(im, re);
}

void start_ring(RingSums& ring, TurnProduct& turn, Vec3& normal, double& area) {
  ring = {Vec3::Zero(), 0.0};
  turn = {1.0, 0.0};
  normal = Vec3::Zero();
  area = 0.0;
}

// The angle sum Σθ is the argument of the product of the complex numbers
// u·v + i|u×v| = |u||v| (cos θ + i sin θ), plus the whole turns, which the sum of the corners'
// approximate angles θ̃ tells (each within 1e-5 of θ: vertex_normals.hpp). The deficit of a
// nearly flat vertex is then the small argument itself, not the difference of two numbers near
// 2π, and it costs one atan2 per vertex instead of one per corner. The factors are not
// normalised by |u||v| (a square root and a division per corner) but by a power of two that
// brings their larger part into [1, 2) (face_terms), which is exact: the argument is that
// of the unit product up to round-off. So the product's magnitude only grows, by less than 2√2 a
// corner; it is brought back by a power of two where it passes 2^500 (a vertex of some 300
// faces), so that it never overflows.
constexpr double turn_renormalise_above = 0x1p500;
// The turns are read off Σθ̃ while it is surely within π of Σθ; vertices of more faces than this
// (no surface a simulation makes) are left to their neighbours (`extrapolated`).
constexpr std::size_t largest_turn_counted_valence = 100000;
static_assert(largest_turn_counted_valence * 1e-5 < std::numbers::pi);

void add_corner(const CornerTerms& terms, RingSums& ring, TurnProduct& turn, Vec3& normal,
                double& area) {
  ring.laplacian += terms.laplacian;
  ring.approximate_angle += terms.approximate_angle;
  normal += terms.normal;
  area += terms.area;
  // Written out: std::complex's operator* and abs guard against inf/NaN at several times the cost.
  const double re = terms.turn_re, im = terms.turn_im;
  const double next_re = turn.re * re - turn.im * im;
  const double next_im = turn.re * im + turn.im * re;
  turn = {next_re, next_im};
  const double magnitude = std::max(std::abs(next_re), std::abs(next_im));
  if (!(magnitude < turn_renormalise_above)) [[unlikely]] {
    const double normaliser = power_of_two_below(magnitude);
    turn = {next_re * normaliser, next_im * normaliser};
  }
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

// All zero, status `undefined`. The status byte is stored through atomic_ref: in
// extrapolate_from_neighbours another chunk may read it meanwhile.
void set_undefined(CurvatureField& field, std::size_t v) {
  set_curvature(field, v, 0.0, 0.0);
  std::atomic_ref<CurvatureStatus>(field.status[v])
      .store(CurvatureStatus::undefined, std::memory_order_relaxed);
}

struct GatherInput {
  const TriangleMesh& mesh;
  const MeshTopology& topology;
  double scale;
  // Without it, the Laplacian's cotangents come from the faces' positions; with it, from its
  // faces and lengths. Angles, normal and area always come from the mesh's own faces.
  const IntrinsicTriangulation* intrinsic;
  // The vertices whose faces lie in more than one chunk of the face pass, in ascending order
  // and once each (empty in the face pass itself, which finds them).
  std::span<const std::int32_t> spanning;
  RingSums* rings;     // per vertex
  TurnProduct* turns;  // per vertex
};

struct GatherCounts {
  std::size_t shapeless = 0, mollified = 0, caps = 0;
  double mollification = 0.0;
};

// A chunk's list of the corners of its faces whose first face lies in an earlier chunk (a
// corner once for each such face). Out of line: a vertex on a chunk's border is rare, and the
// push inlined into the face pass cost it registers.
[[gnu::noinline, gnu::cold]] void list_spanning(std::vector<std::int32_t>& spanning,
                                                std::int32_t v) {
  spanning.push_back(v);
}

// The face pass over faces [begin, end): each face's terms are computed once and added to the
// sums of those of its corners whose first face lies in [begin, end). The first face of a
// vertex starts its sums, so no array needs clearing beforehand. A vertex whose faces all lie
// in one chunk is thus summed in the order of its faces, which is the order of its row
// (build_vertex_faces fills each row in ascending face order). A vertex with faces in two
// chunks is listed by the later chunk, and the vertex pass sums it again from its row, in that
// same order: either way the same sums, whatever the number of chunks.
// The counts are kept on the stack and stored once: the workers' counts share a cache line,
// and adding to them in place made the two cores take that line from each other at every face.
void sum_faces(const GatherInput& in, std::size_t begin, std::size_t end, CurvatureField& field,
               GatherCounts& counts_out, std::vector<std::int32_t>& spanning) {
  GatherCounts counts;
  const VertexFaces& vf = in.topology.vertex_faces;
  for (std::size_t f = begin; f < end; ++f) {
    const Triangle& t = in.mesh.triangles[f];
    if (has_repeated_corner(t)) continue;  // in no row (topology.hpp)
    const FaceTerms face = face_terms(in.mesh, t, in.scale);
    if (face.shapeless) {
      ++counts.shapeless;
    } else {
      const double mollification = face_mollification(face);
      if (mollification > 0.0) {
        ++counts.mollified;
        counts.mollification = std::max(counts.mollification, mollification);
      }
      counts.caps += face.cap;
    }
    for (int corner = 0; corner < 3; ++corner) {
      const std::int32_t v = t[corner];
      // The chunk of v's first face sums v. If v's faces reach into a later chunk, that chunk
      // lists v and the vertex pass sums it again from the start; the first chunk's partial
      // sums are never read.
      const auto first = static_cast<std::size_t>(vf.face_indices[vf.offsets[v]]);
      if (first < begin) {
        list_spanning(spanning, v);
        continue;
      }
      if (first == f) start_ring(in.rings[v], in.turns[v], field.normal[v], field.area[v]);
      add_corner(face.corner[corner], in.rings[v], in.turns[v], field.normal[v], field.area[v]);
    }
  }
  counts_out = counts;
}

// The sums of vertex v from its row, by the same face_terms as the face pass, so with the same
// bits for each face's terms.
void sum_row(const GatherInput& in, std::int32_t vertex, CurvatureField& field) {
  const auto v = static_cast<std::size_t>(vertex);
  start_ring(in.rings[v], in.turns[v], field.normal[v], field.area[v]);
  for (std::int32_t f : in.topology.vertex_faces.of(vertex)) {
    const Triangle& t = in.mesh.triangles[f];
    add_corner(face_terms(in.mesh, t, in.scale).corner[corner_of(t, vertex)], in.rings[v],
               in.turns[v], field.normal[v], field.area[v]);
  }
}

// The vertex pass over vertices [begin, end): sums again the vertices with faces in two chunks,
// starts those in no face (which the face pass never saw) with empty sums, then turns every
// vertex's sums into its fields.
void finish_vertices(const GatherInput& in, std::size_t begin, std::size_t end,
                     CurvatureField& field) {
  const VertexFaces& vf = in.topology.vertex_faces;
  const double scale = in.scale, scale2 = scale * scale;
  for (auto it = std::lower_bound(in.spanning.begin(), in.spanning.end(),
                                  static_cast<std::int32_t>(begin));
       it != in.spanning.end() && static_cast<std::size_t>(*it) < end; ++it)
    sum_row(in, *it, field);
  for (std::size_t v = begin; v < end; ++v) {
    const auto vertex = static_cast<std::int32_t>(v);
    const auto valence = static_cast<std::size_t>(vf.offsets[v + 1] - vf.offsets[v]);
    RingSums& ring = in.rings[v];
    TurnProduct& turn = in.turns[v];
    if (valence == 0) start_ring(ring, turn, field.normal[v], field.area[v]);
    Vec3 laplacian = ring.laplacian;
    const double approximate_angle_sum = ring.approximate_angle;
    if (in.intrinsic) {
      // The Laplacian from the intrinsic triangulation's faces instead of the mesh's.
      laplacian = Vec3::Zero();
      const Vec3 x = in.mesh.positions[v] * scale;
      for (std::int32_t f : in.intrinsic->vertex_faces.of(vertex)) {
        const Triangle& t = in.intrinsic->faces[f];
        const auto& l = in.intrinsic->lengths[f];
        const int corner = corner_of(t, vertex);
        const int next = (corner + 1) % 3, last = (corner + 2) % 3;
        const Vec3 xa = in.mesh.positions[t[next]] * scale - x;
        const Vec3 xb = in.mesh.positions[t[last]] * scale - x;
        add_laplacian_terms(laplacian, l[corner], l[last], l[next], xa, xb);
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
    // A NaN angle sum: a corner of a shapeless face.
    if (kind != VertexKind::interior || std::isnan(approximate_angle_sum) ||
        valence > largest_turn_counted_valence) {
      field.status[v] = CurvatureStatus::extrapolated;
      continue;
    }
    // Σθ = arg + 2π·turns, the argument that of the product brought into [1, 2) (atan2 need not
    // be exact under scaling), the turns those that bring it nearest Σθ̃.
    const double normaliser = power_of_two_below(std::max(std::abs(turn.re), std::abs(turn.im)));
    const double argument = turn_argument(turn.re * normaliser, turn.im * normaliser);
    const double turns =
        std::nearbyint((approximate_angle_sum - argument) / (2.0 * std::numbers::pi));
    const double angle_deficit = -(argument + 2.0 * std::numbers::pi * (turns - 1.0));
    // In scaled units, then back: K ∝ 1/s², H ∝ 1/s.
    const double gaussian = angle_deficit / ring_area * scale2;
    const double projected = laplacian.dot(field.normal[v]);
    const double length = laplacian.norm();
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

}  // namespace

void set_curvature(CurvatureField& field, std::size_t v, double gaussian, double mean) {
  field.gaussian[v] = gaussian;
  field.mean[v] = mean;
}

void extrapolate_from_neighbours(const TriangleMesh& mesh, const VertexFaces& vf,
                                 CurvatureField& field) {
  // A vertex reads only its `computed` neighbours, which no iteration changes, so the result
  // does not depend on the order. The status of an extrapolated vertex that turns undefined may
  // be read meanwhile by a neighbour's thread (which skips it either way): both go through
  // atomic_ref, so the byte is never torn or raced on.
  CurvatureStatus* const status = field.status.data();
  auto status_of = [status](std::size_t v) {
    return std::atomic_ref<CurvatureStatus>(status[v]).load(std::memory_order_relaxed);
  };
  // Counts are exact in any order, so the threads' counts may be added as they come.
  struct Counts {
    std::size_t undefined = 0, extrapolated = 0;
  };
  const Counts total = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, field.status.size(), serial_below), Counts{},
      [&](const tbb::blocked_range<std::size_t>& range, Counts counts) {
        for (std::size_t v = range.begin(); v < range.end(); ++v) {
          const CurvatureStatus own = status_of(v);
          counts.undefined += own == CurvatureStatus::undefined;
          if (own != CurvatureStatus::extrapolated) continue;
          double gaussian = 0.0, mean = 0.0;
          int count = 0;
          for (std::int32_t f : vf.of(static_cast<std::int32_t>(v))) {
            for (std::int32_t w : mesh.triangles[f]) {
              // Neighbours appear in two faces each; counting them twice keeps the mean unchanged.
              if (static_cast<std::size_t>(w) == v || status_of(w) != CurvatureStatus::computed)
                continue;
              gaussian += field.gaussian[w];
              mean += field.mean[w];
              ++count;
            }
          }
          if (count == 0) {
            set_undefined(field, v);
            ++counts.undefined;
          } else {
            set_curvature(field, v, gaussian / count, mean / count);
            ++counts.extrapolated;
          }
        }
        return counts;
      },
      [](Counts a, Counts b) {
        return Counts{a.undefined + b.undefined, a.extrapolated + b.extrapolated};
      });
  field.undefined_vertices = total.undefined;
  field.extrapolated_vertices = total.extrapolated;
}

CurvatureField compute_curvature(const TriangleMesh& mesh, const MeshTopology& topology) {
  const std::size_t n = mesh.positions.size();
  const double scale = power_of_two_scale(mesh.positions);

  // The arrays are zero-filled as they are sized, and the filling (the first touch of every
  // page) costs about as much as a tenth of the gather: half of them on each of two cores.
  CurvatureField field;
  parallel_chunks(2, chunk_count(n), [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t half = begin; half < end; ++half) {
      if (half == 0) {
        field.normal.resize(n);
        field.area.resize(n);
        field.status.resize(n);
      } else {
        field.gaussian.resize(n);
        field.mean.resize(n);
      }
    }
  });

  // Each face's terms are computed once, in a pass over contiguous ranges of faces, one per
  // core; a vertex whose faces all lie in one range is summed there, the few others (faces on
  // both sides of a range's end) afterwards in the vertex pass, in the same order. The first
  // pass also finds the mollification the mesh needs; only a mesh that needs one is summed
  // again with it.
  const std::size_t workers = chunk_count(n);
  const std::size_t m = mesh.triangles.size();
  const auto rings = std::make_unique_for_overwrite<RingSums[]>(n);
  const auto turns = std::make_unique_for_overwrite<TurnProduct[]>(n);
  auto sum_all = [&](const IntrinsicTriangulation* intrinsic) {
    std::vector<GatherCounts> counts(workers);
    std::vector<std::vector<std::int32_t>> chunk_spanning(workers);
    GatherInput input{mesh, topology, scale, intrinsic, {}, rings.get(), turns.get()};
    parallel_chunks(m, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
      std::vector<std::int32_t> spanning;  // moved once: the chunks' vectors share a cache line
      sum_faces(input, begin, end, field, counts[worker], spanning);
      chunk_spanning[worker] = std::move(spanning);
    });
    std::vector<std::int32_t> spanning;
    for (const auto& listed : chunk_spanning)
      spanning.insert(spanning.end(), listed.begin(), listed.end());
    std::sort(spanning.begin(), spanning.end());
    spanning.erase(std::unique(spanning.begin(), spanning.end()), spanning.end());
    input.spanning = spanning;
    parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
      finish_vertices(input, begin, end, field);
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
