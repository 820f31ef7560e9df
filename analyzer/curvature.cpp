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
#include "analyzer/lanes.hpp"
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
// finite at the ends: subnormals take e = −1023, and m ≥ 2^1022, inf and NaN take e = 1022. For
// a double or lanes (lanes.hpp).
template <class Real>
[[gnu::always_inline]] inline Real power_of_two_below(Real m) {
  using Bits = BitsOf<Real>;
  const Real clamped = select(m < 0x1p1022, m, splat<Real>(0x1p1022));
  const Bits biased = (std::bit_cast<Bits>(clamped) >> 52) & 0x7ff;
  return std::bit_cast<Real>((2046 - biased) << 52);
}

// The terms of a block of faces, computed once for their three corners, a lane's worth of faces
// at once, one a lane (lanes.hpp: two with SSE2, four with AVX2). Corner i's neighbours are
// i + 1 and i + 2 (mod 3); edge[i] runs from corner i to corner i + 1. Each corner's terms are
// then laid out as the vertex sums take them (RingSums), so that adding a corner is a few
// whole-vector additions. A block fits in the level-1 cache beside the vertex sums it is added to.
constexpr std::size_t block_faces = 64;
static_assert(block_faces % lanes_of<Lanes4> == 0);

struct FaceBlock {
  // Input: the faces' scaled corner positions, [corner][axis][face].
  alignas(32) double position[3][3][block_faces];
  // Output, per corner and face:
  //   ring: the Laplacian terms from the positions (xyz) and the corner's approximate angle θ̃
  //         (NaN at a face with a zero-length edge, which has no shape and no terms);
  //   normal_area: θ n_face (vertex_normals.hpp) and the corner's share of the mixed Voronoi area;
  //   turn: u·v + i|u×v| times the power of two that brings the larger of its parts into
  //         [1, 2) (add_corner); 1 at a shapeless face.
  alignas(32) double ring[3][block_faces][4];
  alignas(32) double normal_area[3][block_faces][4];
  alignas(32) double turn[3][block_faces][2];
  // Per face, for the counts of the face pass.
  alignas(32) double double_area[block_faces];  // |u × v|
  alignas(32) double length2[3][block_faces];   // squared edge lengths
  alignas(32) double longest2[block_faces];
  alignas(32) std::int64_t shapeless[block_faces];  // nonzero: a zero-length edge
  alignas(32) std::int64_t cap[block_faces];        // nonzero: an angle above 150°

  // Face slot i takes the scaled positions of triangle t.
  void load(std::size_t i, const std::vector<Vec3>& positions, const Triangle& t, double scale) {
    for (int corner = 0; corner < 3; ++corner)
      for (int axis = 0; axis < 3; ++axis)
        position[corner][axis][i] = positions[t[corner]][axis] * scale;
  }
};

// The terms of faces [i, i + lanes) of the block. Every corner takes the same cross
// product u × v = edge[2] × edge[0] and the same reciprocal of its length, so the corners of
// one face agree to the last bit on its plane and area; no lane reads another, so a face's
// terms are the same bits whichever block and lane compute them.
template <class Lanes>
[[gnu::always_inline]] inline void compute_face_lanes(FaceBlock& block, std::size_t i) {
  using LaneMask = MaskOf<Lanes>;
  Lanes edge[3][3];
  for (int axis = 0; axis < 3; ++axis) {
    const Lanes p0 = load_lanes<Lanes>(&block.position[0][axis][i]);
    const Lanes p1 = load_lanes<Lanes>(&block.position[1][axis][i]);
    const Lanes p2 = load_lanes<Lanes>(&block.position[2][axis][i]);
    edge[0][axis] = p1 - p0;
    edge[1][axis] = p2 - p1;
    edge[2][axis] = p0 - p2;
  }
  const Lanes length2[3] = {dot3(edge[0], edge[0]), dot3(edge[1], edge[1]), dot3(edge[2], edge[2])};
  const LaneMask shapeless = is_shapeless_triangle(length2[0], length2[1], length2[2]);
  const Lanes cross[3] = {edge[2][1] * edge[0][2] - edge[2][2] * edge[0][1],
                          edge[2][2] * edge[0][0] - edge[2][0] * edge[0][2],
                          edge[2][0] * edge[0][1] - edge[2][1] * edge[0][0]};
  const Lanes double_area = square_root(dot3(cross, cross));
  // At corner i, u = edge[i] and v = −edge[i + 2].
  const Lanes corner_dot[3] = {-dot3(edge[0], edge[2]), -dot3(edge[1], edge[0]),
                               -dot3(edge[2], edge[1])};
  const Lanes longest2 = maximum(maximum(length2[0], length2[1]), length2[2]);
  const Lanes inverse_area = 1.0 / double_area;
  const Lanes smallest_dot = minimum(minimum(corner_dot[0], corner_dot[1]), corner_dot[2]);
  const LaneMask cap = smallest_dot < cap_cotangent * double_area;
  // Mixed Voronoi area (Meyer et al. 2002, Fig. 4), always the mesh's own.
  const Lanes cot[3] = {corner_dot[0] * inverse_area, corner_dot[1] * inverse_area,
                        corner_dot[2] * inverse_area};
  const LaneMask obtuse = corner_dot[0] < 0.0 || corner_dot[1] < 0.0 || corner_dot[2] < 0.0;
  for (int c = 0; c < 3; ++c) {
    const int next = c == 2 ? 0 : c + 1, last = c == 0 ? 2 : c - 1;
    const Lanes angle = approximate_angle(double_area, corner_dot[c]);
    // Cotangent Laplacian: edge c → next is weighted by the cotangent at last, edge c → last
    // by that at next.
    Lanes ring[4];
    for (int axis = 0; axis < 3; ++axis)
      ring[axis] =
          select(shapeless, Lanes{}, cot[next] * edge[last][axis] - cot[last] * edge[c][axis]);
    ring[3] = select(shapeless, splat<Lanes>(std::numeric_limits<double>::quiet_NaN()), angle);
    store_records(block.ring[c] + i, ring);
    Lanes normal[3];
    corner_normal_term(cross, double_area, corner_dot[c], longest2, normal);
    const Lanes voronoi = 0.125 * (length2[c] * cot[last] + length2[last] * cot[next]);
    const Lanes area = select(shapeless, Lanes{},
                              select(corner_dot[c] < 0.0, 0.25 * double_area,
                                     select(obtuse, 0.125 * double_area, voronoi)));
    store_records(block.normal_area[c] + i, {normal[0], normal[1], normal[2], area});
    const Lanes turn_scale = power_of_two_below(maximum(absolute(corner_dot[c]), double_area));
    store_pairs(block.turn[c] + i, select(shapeless, splat<Lanes>(1.0), corner_dot[c] * turn_scale),
                select(shapeless, Lanes{}, double_area * turn_scale));
    store_lanes(&block.length2[c][i], length2[c]);
  }
  store_lanes(&block.double_area[i], double_area);
  store_lanes(&block.longest2[i], longest2);
  store_mask(&block.shapeless[i], shapeless);
  store_mask(&block.cap[i], cap);
}

// The terms of the block's first `count` faces (the slots past them hold copies of the first,
// so that whole lanes are computed from finite positions).
template <class Lanes>
[[gnu::always_inline]] inline void compute_faces(FaceBlock& block, std::size_t count) {
  constexpr std::size_t lanes = lanes_of<Lanes>;
  const std::size_t padded = (count + lanes - 1) / lanes * lanes;
  for (std::size_t i = count; i < padded; ++i)
    for (int corner = 0; corner < 3; ++corner)
      for (int axis = 0; axis < 3; ++axis)
        block.position[corner][axis][i] = block.position[corner][axis][0];
  for (std::size_t i = 0; i < padded; i += lanes) compute_face_lanes<Lanes>(block, i);
}

bool is_shapeless(const FaceBlock& block, std::size_t i) { return block.shapeless[i] != 0; }

// The δ that face i of the block needs (≤ 0: none).
double block_mollification(const FaceBlock& block, std::size_t i) {
  return block.double_area[i] >= mollification_area_ratio * block.longest2[i]
             ? 0.0
             : mollification_needed(block.length2[0][i], block.length2[2][i], block.length2[1][i]);
}

// What one vertex sums over its faces, but for its normal and area, which are summed in place
// in the field's arrays: Σ (cot α + cot β)(xᵢ − xⱼ) and Σθ̃ (NaN once a corner of a shapeless
// face was added) in one vector, and the running product of the turn factors.
struct alignas(32) RingSums {
  double value[4];
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
  store_lanes(ring.value, Lanes4{});
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
// brings their larger part into [1, 2) (compute_face_lanes), which is exact: the argument is that
// of the unit product up to round-off. So the product's magnitude only grows, by less than 2√2 a
// corner; it is brought back by a power of two where it passes 2^500 (a vertex of some 300
// faces), so that it never overflows.
constexpr double turn_renormalise_above = 0x1p500;
// The turns are read off Σθ̃ while it is surely within π of Σθ; vertices of more faces than this
// (no surface a simulation makes) are left to their neighbours (`extrapolated`).
constexpr std::size_t largest_turn_counted_valence = 100000;
static_assert(largest_turn_counted_valence * 1e-5 < std::numbers::pi);

[[gnu::always_inline]] inline void add_corner(const FaceBlock& block, std::size_t i, int corner,
                                              RingSums& ring, TurnProduct& turn, Vec3& normal,
                                              double& area) {
  store_lanes(ring.value,
              load_lanes<Lanes4>(ring.value) + load_lanes<Lanes4>(block.ring[corner][i]));
  const double* normal_area = block.normal_area[corner][i];
  normal += Vec3(normal_area[0], normal_area[1], normal_area[2]);
  area += normal_area[3];
  // Written out: std::complex's operator* and abs guard against inf/NaN at several times the cost.
  const double re = block.turn[corner][i][0], im = block.turn[corner][i][1];
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

// The face pass over faces [begin, end): each face's terms are computed once, a block at a
// time, and added to the sums of those of its corners whose first face lies in [begin, end).
// The first face of a vertex starts its sums, so no array needs clearing beforehand. A vertex
// whose faces all lie in one chunk is thus summed in the order of its faces, which is the
// order of its row (build_vertex_faces fills each row in ascending face order). A vertex with
// faces in two chunks is listed by the later chunk, and the vertex pass sums it again from its
// row, in that same order: either way the same sums, whatever the number of chunks. Forced
// inline so that each of the two instantiations below compiles all of it for its own
// instruction set.
// The counts are kept on the stack and stored once: the workers' counts share a cache line,
// and adding to them in place made the two cores take that line from each other at every face.
template <class Lanes>
[[gnu::always_inline]] inline void sum_faces(const GatherInput& in, std::size_t begin,
                                             std::size_t end, CurvatureField& field,
                                             GatherCounts& counts_out,
                                             std::vector<std::int32_t>& spanning) {
  GatherCounts counts;
  const VertexFaces& vf = in.topology.vertex_faces;
  const std::vector<Triangle>& triangles = in.mesh.triangles;
  FaceBlock block;
  for (std::size_t block_begin = begin; block_begin < end; block_begin += block_faces) {
    const std::size_t count = std::min(block_faces, end - block_begin);
    for (std::size_t i = 0; i < count; ++i)
      block.load(i, in.mesh.positions, triangles[block_begin + i], in.scale);
    compute_faces<Lanes>(block, count);
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t f = block_begin + i;
      const Triangle& t = triangles[f];
      if (has_repeated_corner(t)) continue;  // in no row (topology.hpp)
      if (is_shapeless(block, i)) {
        ++counts.shapeless;
      } else {
        const double mollification = block_mollification(block, i);
        if (mollification > 0.0) {
          ++counts.mollified;
          counts.mollification = std::max(counts.mollification, mollification);
        }
        counts.caps += block.cap[i] != 0;
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
        add_corner(block, i, corner, in.rings[v], in.turns[v], field.normal[v], field.area[v]);
      }
    }
  }
  counts_out = counts;
}

// The sums of vertex v from its row, by the same block code as the face pass, so with the
// same bits for each face's terms.
template <class Lanes>
[[gnu::always_inline]] inline void sum_row(const GatherInput& in, std::int32_t vertex,
                                           FaceBlock& block, CurvatureField& field) {
  const std::span<const std::int32_t> row = in.topology.vertex_faces.of(vertex);
  const auto v = static_cast<std::size_t>(vertex);
  start_ring(in.rings[v], in.turns[v], field.normal[v], field.area[v]);
  for (std::size_t piece = 0; piece < row.size(); piece += block_faces) {
    const std::size_t count = std::min(block_faces, row.size() - piece);
    for (std::size_t i = 0; i < count; ++i)
      block.load(i, in.mesh.positions, in.mesh.triangles[row[piece + i]], in.scale);
    compute_faces<Lanes>(block, count);
    for (std::size_t i = 0; i < count; ++i)
      add_corner(block, i, corner_of(in.mesh.triangles[row[piece + i]], vertex), in.rings[v],
                 in.turns[v], field.normal[v], field.area[v]);
  }
}

// The vertex pass over vertices [begin, end): sums again the vertices with faces in two chunks,
// starts those in no face (which the face pass never saw) with empty sums, then turns every
// vertex's sums into its fields.
template <class Lanes>
[[gnu::always_inline]] inline void finish_vertices(const GatherInput& in, std::size_t begin,
                                                   std::size_t end, CurvatureField& field) {
  const VertexFaces& vf = in.topology.vertex_faces;
  const double scale = in.scale, scale2 = scale * scale;
  FaceBlock block;
  for (auto it = std::lower_bound(in.spanning.begin(), in.spanning.end(),
                                  static_cast<std::int32_t>(begin));
       it != in.spanning.end() && static_cast<std::size_t>(*it) < end; ++it)
    sum_row<Lanes>(in, *it, block, field);
  for (std::size_t v = begin; v < end; ++v) {
    const auto vertex = static_cast<std::int32_t>(v);
    const auto valence = static_cast<std::size_t>(vf.offsets[v + 1] - vf.offsets[v]);
    RingSums& ring = in.rings[v];
    TurnProduct& turn = in.turns[v];
    if (valence == 0) start_ring(ring, turn, field.normal[v], field.area[v]);
    Vec3 laplacian(ring.value[0], ring.value[1], ring.value[2]);
    const double approximate_angle_sum = ring.value[3];
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

// The same code for any x86-64 (SSE2, two lanes) and for processors with AVX2 and FMA (four
// lanes), chosen at run time: the portable build must not assume AVX2. This file is compiled
// with floating-point contraction allowed (analyzer/CMakeLists.txt), which on x86-64 only the
// second can use: there a·b + c becomes one fused multiply-add, rounded once. Its results differ
// from the portable path's by round-off only (tested); multiplying by the power-of-two scale
// stays exact, so the scale invariance holds in both. Elsewhere there is only the portable code.
// The AVX2 copy does not earn its place in time: whole `analyze` with the portable copy alone
// differed by under 5 % at 55k and 1M vertices (2026-12-04, bench/meshlab_compare.sh's meshes,
// 7–9 alternating runs); it stays because its fused roundings are the bits of the outputs.
void sum_faces_portable(const GatherInput& in, std::size_t begin, std::size_t end,
                        CurvatureField& field, GatherCounts& counts,
                        std::vector<std::int32_t>& spanning) {
  sum_faces<Lanes2>(in, begin, end, field, counts, spanning);
}
void finish_vertices_portable(const GatherInput& in, std::size_t begin, std::size_t end,
                              CurvatureField& field) {
  finish_vertices<Lanes2>(in, begin, end, field);
}

#if defined(__x86_64__) && defined(__GNUC__)
#define TOONWATER_CURVATURE_AVX2_FMA 1
[[gnu::target("avx2,fma")]] void sum_faces_avx2_fma(const GatherInput& in, std::size_t begin,
                                                    std::size_t end, CurvatureField& field,
                                                    GatherCounts& counts,
                                                    std::vector<std::int32_t>& spanning) {
  sum_faces<Lanes4>(in, begin, end, field, counts, spanning);
}
[[gnu::target("avx2,fma")]] void finish_vertices_avx2_fma(const GatherInput& in, std::size_t begin,
                                                          std::size_t end, CurvatureField& field) {
  finish_vertices<Lanes4>(in, begin, end, field);
}
#endif

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
  bool use_avx2_fma = false;
#ifdef TOONWATER_CURVATURE_AVX2_FMA
  use_avx2_fma = kernel == CurvatureKernel::avx2_fma ||
                 (kernel == CurvatureKernel::fastest && avx2_fma_supported());
#endif
  auto sum_all = [&](const IntrinsicTriangulation* intrinsic) {
    std::vector<GatherCounts> counts(workers);
    std::vector<std::vector<std::int32_t>> chunk_spanning(workers);
    GatherInput input{mesh, topology, scale, intrinsic, {}, rings.get(), turns.get()};
    parallel_chunks(m, workers, [&](std::size_t worker, std::size_t begin, std::size_t end) {
      std::vector<std::int32_t> spanning;  // moved once: the chunks' vectors share a cache line
      auto sum_chunk = [&] {
#ifdef TOONWATER_CURVATURE_AVX2_FMA
        if (use_avx2_fma)
          return sum_faces_avx2_fma(input, begin, end, field, counts[worker], spanning);
#endif
        sum_faces_portable(input, begin, end, field, counts[worker], spanning);
      };
      sum_chunk();
      chunk_spanning[worker] = std::move(spanning);
    });
    std::vector<std::int32_t> spanning;
    for (const auto& listed : chunk_spanning)
      spanning.insert(spanning.end(), listed.begin(), listed.end());
    std::sort(spanning.begin(), spanning.end());
    spanning.erase(std::unique(spanning.begin(), spanning.end()), spanning.end());
    input.spanning = spanning;
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
