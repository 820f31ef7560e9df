// Angle-weighted vertex normals (analyzer/vertex_normals.hpp) against the exact normals of
// analytic surfaces, within bounds that shrink under refinement; exact on planes; degenerate
// faces contribute nothing; the winding decides the side.
#include "analyzer/vertex_normals.hpp"

#include "corpus/analytic_surfaces.hpp"
#include "analyzer/topology.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace toonwater {
namespace {

std::vector<Vec3> normals_of(const TriangleMesh& mesh) {
  return angle_weighted_normals(mesh, build_vertex_faces(mesh.positions.size(), mesh.triangles));
}

// The largest angle (radians) between the computed normal and `exact(p)` over the vertices
// where `use` holds.
template <class Exact, class Use>
double worst_angle(const TriangleMesh& mesh, Exact exact, Use use) {
  const std::vector<Vec3> n = normals_of(mesh);
  double worst = 0.0;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    if (!use(v)) continue;
    const Vec3 e = exact(mesh.positions[v]).normalized();
    worst = std::max(worst, std::atan2(n[v].cross(e).norm(), n[v].dot(e)));
  }
  return worst;
}

TEST(VertexNormals, SpheresPointOutwardWithinABoundThatShrinksWithTheMesh) {
  const auto radial = [](const Vec3& p) { return p; };
  const auto all = [](std::size_t) { return true; };
  const double coarse = worst_angle(make_icosphere(2, 3.0).mesh, radial, all);
  const double fine = worst_angle(make_icosphere(4, 3.0).mesh, radial, all);
  // The icosphere's valence-5 vertices keep the error first order: O(h), h / 4 here.
  EXPECT_LT(coarse, 0.015);  // measured 0.0104
  EXPECT_LT(fine, 0.004);    // measured 0.0026
  EXPECT_LT(fine, coarse / 3);
  // Irregular sampling of the same sphere: still within a degree.
  EXPECT_LT(worst_angle(make_icosphere(4, 3.0, {0.2, 7}).mesh, radial, all),
            std::numbers::pi / 180);
}

TEST(VertexNormals, HeightFieldsAndCylindersWithinBounds) {
  // Saddle z = (x² − y²)/2: n ∝ (−x, y, 1), at interior vertices.
  const AnalyticSurface saddle = make_saddle(65);
  EXPECT_LT(worst_angle(
                saddle.mesh, [](const Vec3& p) { return Vec3(-p.x(), p.y(), 1.0); },
                [&](std::size_t v) { return bool(saddle.interior[v]); }),
            1e-3);
  // Open cylinder around z: radial normals, away from the rims.
  const AnalyticSurface cylinder = make_cylinder(64, 16);
  EXPECT_LT(worst_angle(
                cylinder.mesh, [](const Vec3& p) { return Vec3(p.x(), p.y(), 0.0); },
                [&](std::size_t v) { return bool(cylinder.interior[v]); }),
            1e-9);
}

TEST(VertexNormals, PlanesAreExactWhateverTheTriangulation) {
  TriangleMesh plane = make_saddle(17, 0.5, {0.3, 3}).mesh;
  for (Vec3& p : plane.positions) p.z() = 0.25;
  const Vec3 tilt = Vec3(1, 2, 2).normalized();
  const Eigen::Matrix3d rotate =
      Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), tilt).toRotationMatrix();
  for (Vec3& p : plane.positions) p = rotate * p + Vec3(10, -4, 3);
  for (const Vec3& n : normals_of(plane)) EXPECT_LT((n - tilt).norm(), 1e-12);
}

TEST(VertexNormals, DegenerateFacesContributeNothing) {
  TriangleMesh mesh = make_saddle(9).mesh;
  const std::vector<Vec3> before = normals_of(mesh);
  // A collinear sliver on vertices 0 and 1 (a new vertex between them), and a face of zero area
  // on three coincident points: neither changes a normal; a vertex only in them gets none.
  const auto mid = static_cast<std::int32_t>(mesh.positions.size());
  mesh.positions.push_back(0.5 * (mesh.positions[0] + mesh.positions[1]));
  mesh.positions.push_back(mesh.positions[40]);
  mesh.positions.push_back(mesh.positions[40]);
  mesh.triangles.push_back({0, mid, 1});
  mesh.triangles.push_back({40, mid + 1, mid + 2});
  const std::vector<Vec3> after = normals_of(mesh);
  for (std::size_t v = 0; v < before.size(); ++v) EXPECT_EQ(after[v], before[v]) << "vertex " << v;
  for (std::size_t v = before.size(); v < after.size(); ++v) EXPECT_EQ(after[v], Vec3::Zero());
  EXPECT_EQ(corner_normal_term(Vec3(1, 0, 0), Vec3(2, 0, 0)), Vec3::Zero());
  // Doubled area 1e-13 against a longest squared edge of 1: below degenerate_area_ratio.
  EXPECT_EQ(corner_normal_term(Vec3(1, 0, 0), Vec3(1, 1e-13, 0)), Vec3::Zero());
  EXPECT_NE(corner_normal_term(Vec3(1, 0, 0), Vec3(1, 1e-11, 0)), Vec3::Zero());
}

TEST(VertexNormals, TheWindingDecidesTheSide) {
  TriangleMesh sphere = make_icosphere(2).mesh;
  const std::vector<Vec3> outward = normals_of(sphere);
  for (Triangle& t : sphere.triangles) std::swap(t[1], t[2]);
  const std::vector<Vec3> inward = normals_of(sphere);
  for (std::size_t v = 0; v < outward.size(); ++v) {
    EXPECT_GT(outward[v].dot(sphere.positions[v]), 0.99);
    EXPECT_LT((inward[v] + outward[v]).norm(), 1e-15);
  }
}

TEST(VertexNormals, TheAngleApproximationIsWithinItsBound) {
  double worst = 0.0;
  for (int i = 0; i <= 10000; ++i) {
    const double a = std::numbers::pi * i / 10000;
    for (double r : {1e-3, 1.0, 1e6})
      worst = std::max(worst, std::abs(approximate_angle(r * std::sin(a), r * std::cos(a)) - a));
  }
  EXPECT_LT(worst, 1e-5);
}

}  // namespace
}  // namespace toonwater
