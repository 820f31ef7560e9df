// Stiff and extreme cases: degenerate faces, slivers, extreme coordinates, broken topology.
// Every case asserts that the outputs stay finite and what the values are.
#include "tests/analyzer/curvature_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace toonwater::test {
namespace {

// A flat n×n grid in the z = 0 plane, triangles counter-clockwise from +z.
TriangleMesh flat_grid(int n, double step = 1.0) {
  return make_saddle(n, 0.5 * step * (n - 1)).mesh;  // then flattened below
}

TriangleMesh plane(int n) {
  TriangleMesh m = flat_grid(n);
  for (Vec3& p : m.positions) p.z() = 0.0;
  return m;
}

// Splits edge {a, b} of `mesh` at a new vertex m on one side only and closes the T-junction
// with the collinear face (a, b, m), as marching-cubes output and mesh simplifiers leave them.
// The new vertex is displaced by `offset` from the edge's midpoint.
std::int32_t insert_t_junction(TriangleMesh& mesh, std::int32_t a, std::int32_t b,
                               const Vec3& offset) {
  const auto m = static_cast<std::int32_t>(mesh.positions.size());
  mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]) + offset);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    Triangle& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] == a && t[(c + 1) % 3] == b) {  // the face traversing a→b
        const std::int32_t opposite = t[(c + 2) % 3];
        t = {a, m, opposite};
        mesh.triangles.push_back({m, b, opposite});
        mesh.triangles.push_back({a, b, m});  // the cap: angle π (or nearly) at m
        return m;
      }
    }
  }
  ADD_FAILURE() << "edge not found";
  return m;
}

TEST(CurvatureStability, CollinearFaceInAPlaneKeepsKAndHZero) {
  TriangleMesh m = plane(9);
  const std::int32_t centre = 4 * 9 + 4;
  const std::int32_t added = insert_t_junction(m, centre, centre + 9, Vec3::Zero());
  const Curvature c = curvature_of(m);
  EXPECT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.sliver_faces, 1u);
  EXPECT_EQ(c.topology.kind[added], VertexKind::interior);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (c.topology.kind[v] != VertexKind::interior) continue;
    const bool at_cap = v == static_cast<std::size_t>(added) || v == static_cast<std::size_t>(centre) ||
                        v == static_cast<std::size_t>(centre + 9);
    EXPECT_EQ(c.field.status[v], at_cap ? CurvatureStatus::extrapolated : CurvatureStatus::computed) << v;
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12) << v;
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12) << v;
  }
}

TEST(CurvatureStability, CapsAndNeedlesBelowATenThousandthOfADegreeOnASphere) {
  // On a sphere, put a vertex a hair off an edge's midpoint: the cap's angle at it is within
  // 1e-4° of 180°, and its two other angles are needles below 1e-4°.
  AnalyticSurface s = make_icosphere(4);
  TriangleMesh& m = s.mesh;
  const Triangle t0 = m.triangles[0];
  const Vec3 a = m.positions[t0[0]], b = m.positions[t0[1]];
  const double edge = (b - a).norm();
  const Vec3 outward = (0.5 * (a + b)).normalized();
  const std::int32_t added = insert_t_junction(m, t0[0], t0[1], 1e-8 * edge * outward);
  const Curvature c = curvature_of(m);
  ASSERT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.sliver_faces, 1u);
  // The cap has an area (it is not collinear) but angles far below 3°: a sliver.
  const Triangle cap = m.triangles.back();
  const Vec3 u = m.positions[cap[0]] - m.positions[cap[2]], w = m.positions[cap[1]] - m.positions[cap[2]];
  const double cap_angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi;
  EXPECT_GT(cap_angle, 180.0 - 1e-4);
  EXPECT_LT(cap_angle, 180.0);
  // The cap's corners take their neighbours' values; nowhere does the sliver make a spike.
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const bool at_cap = v == static_cast<std::size_t>(added) || v == static_cast<std::size_t>(t0[0]) ||
                        v == static_cast<std::size_t>(t0[1]);
    EXPECT_EQ(c.field.status[v], at_cap ? CurvatureStatus::extrapolated : CurvatureStatus::computed);
    EXPECT_NEAR(c.field.mean[v], 1.0, 0.05) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 0.1) << v;
  }
}

TEST(CurvatureStability, ObtuseTrianglesNearOneEightyDegrees) {
  // A low convex cone whose apex sits just inside one edge of its hexagonal base: the face on
  // that edge has an angle of about 170° at the apex. (Above 177° the face would be a sliver,
  // left out; see the caps test.) Meyer's rule gives the apex half of that face's area.
  TriangleMesh m;
  const int ring = 6;
  for (int i = 0; i < ring; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / ring;
    m.positions.emplace_back(std::cos(phi), std::sin(phi), 0.0);
  }
  const Vec3 edge_midpoint = 0.5 * (m.positions[0] + m.positions[1]);
  m.positions.push_back(0.9495 * edge_midpoint + Vec3(0, 0, 0.001));
  const std::int32_t apex = ring;
  for (int i = 0; i < ring; ++i) m.triangles.push_back({apex, i, (i + 1) % ring});
  const Curvature c = curvature_of(m);
  ASSERT_TRUE(all_finite(c.field));
  const Vec3 u = m.positions[0] - m.positions[apex], w = m.positions[1] - m.positions[apex];
  EXPECT_GT(std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi, 169.0);
  EXPECT_EQ(c.field.sliver_faces, 0u);
  EXPECT_EQ(c.field.status[apex], CurvatureStatus::computed);
  double angle_sum = 0.0;
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.positions[t[1]] - m.positions[apex], b = m.positions[t[2]] - m.positions[apex];
    angle_sum += std::atan2(a.cross(b).norm(), a.dot(b));
  }
  // The mixed area by Meyer's three cases, computed independently...
  double expected_area = 0.0;
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.positions[t[1]] - m.positions[apex], b = m.positions[t[2]] - m.positions[apex];
    const double face_area = 0.5 * a.cross(b).norm();
    const bool obtuse_at_apex = a.dot(b) < 0.0;
    const bool obtuse_elsewhere = (m.positions[apex] - m.positions[t[1]]).dot(m.positions[t[2]] - m.positions[t[1]]) < 0.0 ||
                                  (m.positions[apex] - m.positions[t[2]]).dot(m.positions[t[1]] - m.positions[t[2]]) < 0.0;
    if (obtuse_at_apex) expected_area += face_area / 2;
    else if (obtuse_elsewhere) expected_area += face_area / 4;
    else {
      const double cot_1 = (m.positions[apex] - m.positions[t[1]]).dot(m.positions[t[2]] - m.positions[t[1]]) / (2 * face_area);
      const double cot_2 = (m.positions[apex] - m.positions[t[2]]).dot(m.positions[t[1]] - m.positions[t[2]]) / (2 * face_area);
      expected_area += (b.squaredNorm() * cot_1 + a.squaredNorm() * cot_2) / 8;
    }
  }
  // ...so K and the area follow Meyer's obtuse rules exactly.
  EXPECT_NEAR(c.field.area[apex], expected_area, 1e-15);
  EXPECT_NEAR(c.field.gaussian[apex], (2.0 * std::numbers::pi - angle_sum) / expected_area, 1e-9);
  EXPECT_GT(c.field.gaussian[apex], 0.0);  // a convex cone
  EXPECT_GT(c.field.mean[apex], 0.0);
}

TEST(CurvatureStability, RepeatedCornersAndZeroLengthEdgesAreLeftOut) {
  TriangleMesh m = plane(5);
  m.triangles.push_back({6, 6, 7});  // repeated corner
  m.positions.push_back(m.positions[12]);  // a coincident copy of the centre vertex
  m.triangles.push_back({12, 25, 13});     // zero-length edge 12–25
  const Curvature c = curvature_of(m);
  EXPECT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.sliver_faces, 2u);
  EXPECT_NEAR(c.field.gaussian[6], 0.0, 1e-12);
  EXPECT_EQ(c.field.status[25], CurvatureStatus::undefined);
}

std::vector<std::pair<double, double>> kh_of(const TriangleMesh& m) {
  const Curvature c = curvature_of(m);
  std::vector<std::pair<double, double>> kh;
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    kh.emplace_back(c.field.gaussian[v], c.field.mean[v]);
  return kh;
}

TEST(CurvatureStability, TranslationByAMillion) {
  // A 1e6 offset costs the coordinates log2(1e6) ≈ 20 of their 53 bits: edges of ~0.1 keep
  // about 1e-10 / 0.1 relative precision, and second differences (curvature) amplify that by
  // the ratio of size to edge. 1e-6 relative covers it with margin; measured ~1e-8.
  const AnalyticSurface s = make_wave_field(65);
  TriangleMesh moved = s.mesh;
  for (Vec3& p : moved.positions) p += Vec3(1e6, -1e6, 1e6);
  const auto reference = kh_of(s.mesh), translated = kh_of(moved);
  for (std::size_t v = 0; v < reference.size(); ++v) {
    if (!s.interior[v]) continue;
    EXPECT_NEAR(translated[v].first, reference[v].first, 1e-6 * (std::abs(reference[v].first) + 1.0));
    EXPECT_NEAR(translated[v].second, reference[v].second, 1e-6 * (std::abs(reference[v].second) + 1.0));
  }
}

TEST(CurvatureStability, ScalingByAMillionthAndAMillion) {
  const AnalyticSurface s = make_torus(48, 24);
  const auto reference = kh_of(s.mesh);
  for (double scale : {1e-6, 1e6, 0x1p-20, 1e-150, 1e150}) {
    SCOPED_TRACE(scale);
    TriangleMesh scaled = s.mesh;
    for (Vec3& p : scaled.positions) p *= scale;
    const Curvature c = curvature_of(scaled);
    ASSERT_TRUE(all_finite(c.field));
    for (std::size_t v = 0; v < reference.size(); ++v) {
      // K ∝ 1/s², H ∝ 1/s; only the rounding of the scaled input remains (~1e-15 relative,
      // amplified by size/edge ≈ 10 in the second differences).
      EXPECT_NEAR(c.field.gaussian[v] * scale * scale, reference[v].first,
                  1e-11 * std::abs(reference[v].first) + 1e-10);
      EXPECT_NEAR(c.field.mean[v] * scale, reference[v].second, 1e-11 * std::abs(reference[v].second));
    }
  }
}

TEST(CurvatureStability, RotationInvariance) {
  const AnalyticSurface s = make_ellipsoid(4);
  const auto reference = kh_of(s.mesh);
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  TriangleMesh rotated = s.mesh;
  for (Vec3& p : rotated.positions) p = rotation * p;
  const auto turned = kh_of(rotated);
  for (std::size_t v = 0; v < reference.size(); ++v) {
    EXPECT_NEAR(turned[v].first, reference[v].first, 1e-11 * std::abs(reference[v].first));
    EXPECT_NEAR(turned[v].second, reference[v].second, 1e-11 * std::abs(reference[v].second));
  }
}

TEST(CurvatureStability, BoundaryVerticesTakeTheirNeighboursMean) {
  const AnalyticSurface s = make_cylinder(32, 16, 1.0, 2.0);
  const Curvature c = curvature_of(s.mesh);
  EXPECT_EQ(c.topology.boundary_vertices, 64u);
  EXPECT_EQ(c.topology.boundary_edges, 64u);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    if (c.topology.kind[v] != VertexKind::boundary) continue;
    EXPECT_EQ(c.field.status[v], CurvatureStatus::extrapolated);
    EXPECT_NEAR(c.field.mean[v], 0.5, 1e-9);  // a rim vertex's own one-ring would give ~0.25
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-9);
    EXPECT_GT(c.field.area[v], 0.0);
  }
}

TEST(CurvatureStability, IsolatedVertexIsUndefinedAndCounted) {
  TriangleMesh m = make_icosphere(2).mesh;
  m.positions.emplace_back(5, 5, 5);
  const Curvature c = curvature_of(m);
  EXPECT_EQ(c.topology.isolated_vertices, 1u);
  EXPECT_EQ(c.field.status.back(), CurvatureStatus::undefined);
  EXPECT_EQ(c.field.undefined_vertices, 1u);
  EXPECT_EQ(c.field.gaussian.back(), 0.0);
  EXPECT_TRUE(all_finite(c.field));
}

TEST(CurvatureStability, NonManifoldVertexAndEdge) {
  // Two spheres touching at one vertex (a bow tie of fans), and a fin: a third face on an edge.
  TriangleMesh m = make_icosphere(2).mesh;
  const auto n = static_cast<std::int32_t>(m.positions.size());
  const std::size_t face_count = m.triangles.size();
  const Vec3 apex = m.positions[0];
  for (std::int32_t v = 0; v < n; ++v) m.positions.push_back(2.0 * apex - m.positions[v]);
  for (std::size_t f = 0; f < face_count; ++f) {
    Triangle t = m.triangles[f];
    for (std::int32_t& v : t) v = v == 0 ? 0 : v + n;  // share vertex 0
    std::swap(t[1], t[2]);  // point reflection reverses orientation; restore outward normals
    m.triangles.push_back(t);
  }
  const Triangle first = m.triangles[5];
  m.positions.push_back(m.positions[first[0]] * 1.5);
  m.triangles.push_back({first[0], first[1], static_cast<std::int32_t>(m.positions.size() - 1)});
  const Curvature c = curvature_of(m);
  EXPECT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.topology.kind[0], VertexKind::nonmanifold);
  EXPECT_EQ(c.topology.kind[first[0]], VertexKind::nonmanifold);
  EXPECT_EQ(c.topology.nonmanifold_edges, 1u);
  EXPECT_EQ(c.field.status[0], CurvatureStatus::extrapolated);
  EXPECT_GT(c.field.mean[0], 0.5);  // the spheres' curvature, not an angle sum of 4π
  EXPECT_EQ(c.topology.components, 1u);
}

TEST(CurvatureStability, SingleTriangleAndEmptyMesh) {
  TriangleMesh tri;
  tri.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  tri.triangles = {{0, 1, 2}};
  const Curvature c = curvature_of(tri);
  EXPECT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.topology.boundary_vertices, 3u);
  EXPECT_EQ(c.field.undefined_vertices, 3u);  // no vertex has a computed neighbour
  EXPECT_NEAR(c.field.area[0] + c.field.area[1] + c.field.area[2], 0.5, 1e-15);

  const Curvature empty = curvature_of(TriangleMesh{});
  EXPECT_TRUE(empty.field.gaussian.empty());
  EXPECT_EQ(empty.topology.components, 0u);
}

TEST(CurvatureStability, FlatPlaneIsZeroToRoundOff) {
  TriangleMesh m = plane(33);
  for (Vec3& p : m.positions) p = Vec3(p.x() * 3.0 + 0.1 * p.y(), p.y() * 0.5, 0.0);  // sheared
  const Curvature c = curvature_of(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12);
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12);
  }
}

TEST(CurvatureStability, InconsistentWindingIsRepairedAndCounted) {
  AnalyticSurface s = make_icosphere(3);
  std::size_t reversed = 0;
  for (std::size_t f = 0; f < s.mesh.triangles.size(); f += 7, ++reversed)
    std::swap(s.mesh.triangles[f][1], s.mesh.triangles[f][2]);
  const Curvature c = curvature_of(s.mesh);
  EXPECT_EQ(c.flipped, reversed);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    EXPECT_NEAR(c.field.mean[v], 1.0, 1e-2);
    EXPECT_GT(c.field.normal[v].dot(s.mesh.positions[v]), 0.99);
  }
}

}  // namespace
}  // namespace toonwater::test
