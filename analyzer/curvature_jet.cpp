// Curvature from osculating jets (Cazals and Pouget 2005); formulas in curvature_jet.hpp.
//
// Choices:
// - Neighbourhood: the two-ring (about 19 points on a valence-6 mesh, twice the cubic's 10
//   coefficients). It is not grown through non-manifold vertices, whose other sheets would be
//   outliers of the fit, nor through a vertex of more than 256 faces: such a hub (a fan of
//   thousands, as degenerate or hostile input has) would put its whole fan, far from the
//   neighbour being fitted, into the fit of each of its neighbours, at a cost quadratic in its
//   faces (a fan of 100,000 took over a minute; now milliseconds). Too few points for the
//   cubic (below 15, e.g. at a boundary corner): a quadric (6 coefficients, O(h) error) if
//   there are at least 9.
// - Conditioning: coordinates relative to p, divided by the neighbourhood's radius ρ (its largest
//   coordinate offset), so the monomials lie in [−1, 1] whatever the scene's scale and offset; no
//   squared length is formed before the division, so coordinates near 1e±150 neither overflow
//   nor underflow. The normal equations are solved by LDLT with pivoting; a fit whose smallest
//   pivot is below 1e-12 of the largest (points on a curve, not a surface patch) is rejected.
// - The frame's tangent axes are any orthonormal pair: polynomials of degree ≤ 3 are closed under
//   rotations of (u, v), so the fitted graph, and its K and H, do not depend on that choice.
// - Boundary vertices are fitted from their one-sided neighbourhoods (the fit needs positions,
//   not a closed fan). Non-manifold vertices and rejected fits take the mean of their fitted
//   neighbours (status `extrapolated`), as in the one-ring estimator; with none, zeros
//   (`undefined`). Slivers need no special case: they only contribute their corners' positions.
#include "analyzer/curvature_jet.hpp"

#include "common/parallel.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>

namespace toonwater {
namespace {

constexpr std::size_t cubic_min_points = 15;
constexpr std::size_t quadric_min_points = 9;
constexpr double min_pivot_ratio = 1e-12;
constexpr std::size_t largest_grown_valence = 256;

struct SurfaceCurvature {
  double gaussian;
  double mean;
};

// The vertices of the faces around v and around its neighbours, v excluded. `mark` holds, per
// vertex, the last centre that collected it.
void gather_two_ring(const TriangleMesh& mesh, const MeshTopology& topology, std::int32_t v,
                     std::vector<std::int32_t>& mark, std::vector<std::int32_t>& ring) {
  ring.clear();
  mark[v] = v;
  auto add_faces_of = [&](std::int32_t centre) {
    for (std::int32_t f : topology.vertex_faces.of(centre))
      for (std::int32_t w : mesh.triangles[f])
        if (mark[w] != v) {
          mark[w] = v;
          ring.push_back(w);
        }
  };
  add_faces_of(v);
  const std::size_t one_ring = ring.size();
  for (std::size_t i = 0; i < one_ring; ++i)
    if (topology.kind[ring[i]] != VertexKind::nonmanifold &&
        topology.vertex_faces.of(ring[i]).size() <= largest_grown_valence)
      add_faces_of(ring[i]);
}

template <int Coefficients>
std::optional<Eigen::Matrix<double, Coefficients, 1>> solve_normal_equations(
    const Eigen::Matrix<double, 10, 10>& normal, const Eigen::Matrix<double, 10, 1>& rhs) {
  const Eigen::LDLT<Eigen::Matrix<double, Coefficients, Coefficients>> ldlt(
      normal.topLeftCorner<Coefficients, Coefficients>());
  if (ldlt.info() != Eigen::Success) return std::nullopt;
  const auto pivots = ldlt.vectorD().cwiseAbs();
  if (!(pivots.minCoeff() > min_pivot_ratio * pivots.maxCoeff())) return std::nullopt;
  return ldlt.solve(rhs.head<Coefficients>());
}

// Fits the jet at p = positions[v] with unit normal n to p and `ring`.
std::optional<SurfaceCurvature> fit_jet(const TriangleMesh& mesh, std::int32_t v, const Vec3& n,
                                        std::span<const std::int32_t> ring) {
  const std::size_t points = ring.size() + 1;
  if (points < quadric_min_points) return std::nullopt;
  const Vec3& p = mesh.positions[v];
  double radius = 0.0;
  for (std::int32_t w : ring)
    radius = std::max(radius, (mesh.positions[w] - p).cwiseAbs().maxCoeff());
  if (!(radius > 0.0) || !std::isfinite(radius)) return std::nullopt;

  // Tangent axes: the coordinate axis least aligned with n, made orthogonal to it.
  Eigen::Index least;
  n.cwiseAbs().minCoeff(&least);
  const Vec3 t1 = Vec3::Unit(least).cross(n).normalized();
  const Vec3 t2 = n.cross(t1);

  // Monomials ordered by degree, so the quadric's system is the cubic's top-left 6×6 block.
  Eigen::Matrix<double, 10, 10> normal = Eigen::Matrix<double, 10, 10>::Zero();
  Eigen::Matrix<double, 10, 1> rhs = Eigen::Matrix<double, 10, 1>::Zero();
  normal(0, 0) = 1.0;  // p itself: u = v = w = 0
  Eigen::Matrix<double, 10, 1> monomials;
  for (std::int32_t w : ring) {
    const Vec3 d = (mesh.positions[w] - p) / radius;
    const double x = d.dot(t1), y = d.dot(t2), height = d.dot(n);
    monomials << 1.0, x, y, x * x, x * y, y * y, x * x * x, x * x * y, x * y * y, y * y * y;
    normal.selfadjointView<Eigen::Lower>().rankUpdate(monomials);  // LDLT reads the lower half
    rhs += height * monomials;
  }

  Eigen::Matrix<double, 6, 1> c;
  if (points >= cubic_min_points) {
    const auto cubic = solve_normal_equations<10>(normal, rhs);
    if (!cubic) return std::nullopt;
    c = cubic->head<6>();
  } else {
    const auto quadric = solve_normal_equations<6>(normal, rhs);
    if (!quadric) return std::nullopt;
    c = *quadric;
  }
  const double wu = c[1], wv = c[2], wuu = 2.0 * c[3], wuv = c[4], wvv = 2.0 * c[5];
  const double w2 = 1.0 + wu * wu + wv * wv;
  // Divided by ρ one factor at a time, so a tiny ρ does not underflow ρ².
  const double gaussian = (wuu * wvv - wuv * wuv) / (w2 * w2) / radius / radius;
  const double mean = -((1.0 + wv * wv) * wuu - 2.0 * wu * wv * wuv + (1.0 + wu * wu) * wvv) /
                      (2.0 * w2 * std::sqrt(w2)) / radius;
  if (!std::isfinite(gaussian) || !std::isfinite(mean)) return std::nullopt;
  return SurfaceCurvature{gaussian, mean};
}

}  // namespace

CurvatureField compute_curvature_jet(const TriangleMesh& mesh, const MeshTopology& topology) {
  CurvatureField field = compute_curvature(mesh, topology);
  const std::size_t n = mesh.positions.size();
  const std::size_t workers = chunk_count(n, 4096);
  parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    std::vector<std::int32_t> mark(n, -1), ring;
    for (std::size_t v = begin; v < end; ++v) {
      const auto vertex = static_cast<std::int32_t>(v);
      const VertexKind kind = topology.kind[v];
      if (kind == VertexKind::isolated || field.normal[v].isZero()) {
        set_curvature(field, v, 0.0, 0.0);
        field.status[v] = CurvatureStatus::undefined;
        continue;
      }
      std::optional<SurfaceCurvature> jet;
      if (kind != VertexKind::nonmanifold) {
        gather_two_ring(mesh, topology, vertex, mark, ring);
        jet = fit_jet(mesh, vertex, field.normal[v], ring);
      }
      if (jet) {
        set_curvature(field, v, jet->gaussian, jet->mean);
        field.status[v] = CurvatureStatus::computed;
      } else {
        field.status[v] = CurvatureStatus::extrapolated;
      }
    }
  });
  extrapolate_from_neighbours(mesh, topology.vertex_faces, field);
  return field;
}

}  // namespace toonwater
