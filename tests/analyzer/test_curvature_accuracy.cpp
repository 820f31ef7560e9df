// Accuracy of K and H against analytic surfaces: error bounds at a fixed resolution and the
// rate at which the error falls under refinement on regular meshes.
//
// Errors are RMS over interior vertices, relative to the RMS of the exact value (cylinder: K
// relative to H²). Bounds are about twice the measured errors, so a regression shows.
#include "tests/analyzer/curvature_test_util.hpp"

#include <gtest/gtest.h>

namespace toonwater::test {
namespace {

// Error ratio between consecutive refinements (mesh spacing halved).
void expect_convergence(const std::vector<Errors>& errors, double min_ratio_k, double min_ratio_h) {
  for (std::size_t i = 1; i < errors.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "refinement " << i);
    EXPECT_GT(errors[i - 1].gaussian / errors[i].gaussian, min_ratio_k);
    EXPECT_GT(errors[i - 1].mean / errors[i].mean, min_ratio_h);
  }
}

TEST(CurvatureAccuracy, IcosphereConvergesQuadraticallyPastAMillionVertices) {
  // Subdivision levels 3..9: 642 to 2.6M vertices. A single-precision implementation stops
  // improving near 55k vertices; double precision keeps the O(h²) rate throughout.
  std::vector<Errors> errors;
  for (int level = 3; level <= 9; ++level) errors.push_back(relative_errors(make_icosphere(level, 2.0)));
  expect_convergence(errors, 3.5, 3.0);
  EXPECT_LT(errors.back().gaussian, 2e-6);
  EXPECT_LT(errors.back().mean, 2e-9);
}

TEST(CurvatureAccuracy, UvSphere) {
  std::vector<Errors> errors;
  for (int rings : {16, 32, 64, 128}) errors.push_back(relative_errors(make_uv_sphere(rings, 2 * rings)));
  expect_convergence(errors, 3.5, 3.0);
  EXPECT_LT(errors.back().gaussian, 3e-4);
  EXPECT_LT(errors.back().mean, 1e-4);
}

TEST(CurvatureAccuracy, Torus) {
  std::vector<Errors> errors;
  for (int n : {16, 32, 64, 128}) errors.push_back(relative_errors(make_torus(2 * n, n)));
  expect_convergence(errors, 3.5, 3.5);
  EXPECT_LT(errors.back().gaussian, 5e-4);
  EXPECT_LT(errors.back().mean, 2e-4);
}

TEST(CurvatureAccuracy, EllipsoidConvergesLinearlyOnAStretchedIcosphere) {
  // The stretched icosphere's triangles are not regular, so the rate drops to O(h).
  std::vector<Errors> errors;
  for (int level = 2; level <= 6; ++level) errors.push_back(relative_errors(make_ellipsoid(level)));
  expect_convergence(errors, 1.8, 1.8);
  EXPECT_LT(errors.back().gaussian, 2e-3);
  EXPECT_LT(errors.back().mean, 1.5e-3);
}

TEST(CurvatureAccuracy, CylinderIsExactUpToRoundOff) {
  const AnalyticSurface s = make_cylinder(64, 64, 0.5, 2.0);
  const Curvature c = curvature_of(s.mesh);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    if (!s.interior[v]) continue;
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-9);
    EXPECT_NEAR(c.field.mean[v], 1.0, 1e-12);
    EXPECT_NEAR(c.field.k1[v], 2.0, 1e-6);
    EXPECT_NEAR(c.field.k2[v], 0.0, 1e-6);
  }
}

TEST(CurvatureAccuracy, Saddle) {
  std::vector<Errors> errors;
  for (int n : {17, 33, 65, 129, 257}) errors.push_back(relative_errors(make_saddle(n)));
  expect_convergence(errors, 3.5, 3.5);
  EXPECT_LT(errors.back().gaussian, 2e-5);
  EXPECT_LT(errors.back().mean, 3e-5);
}

TEST(CurvatureAccuracy, SaddleSigns) {
  const AnalyticSurface s = make_saddle(65);
  const Curvature c = curvature_of(s.mesh);
  const std::size_t centre = 32 * 65 + 32;
  EXPECT_NEAR(c.field.gaussian[centre], -1.0, 1e-3);
  EXPECT_NEAR(c.field.mean[centre], 0.0, 1e-3);
  EXPECT_NEAR(c.field.k1[centre], 1.0, 1e-3);
  EXPECT_NEAR(c.field.k2[centre], -1.0, 1e-3);
}

TEST(CurvatureAccuracy, WaveField) {
  std::vector<Errors> errors;
  for (int n : {33, 65, 129, 257}) errors.push_back(relative_errors(make_wave_field(n)));
  expect_convergence(errors, 3.5, 3.5);
  EXPECT_LT(errors.back().gaussian, 3e-3);
  EXPECT_LT(errors.back().mean, 7e-4);
}

TEST(CurvatureAccuracy, WaveCrestsArePositiveAndTroughsNegative) {
  const AnalyticSurface s = make_wave_field(129);
  const Curvature c = curvature_of(s.mesh);
  std::size_t checked = 0;
  for (std::size_t v = 0; v < s.mean.size(); ++v) {
    if (!s.interior[v] || std::abs(s.mean[v]) < 0.5) continue;  // clear crests and troughs
    EXPECT_EQ(c.field.mean[v] > 0, s.mean[v] > 0) << "vertex " << v;
    ++checked;
  }
  EXPECT_GT(checked, 1000u);
}

// Jittered vertices make the triangulation irregular. K stays accurate; the cotangent H does
// not converge pointwise on such meshes (a known limit of the operator), so only a bound is
// asserted here. Jitter 0.2 of the grid step keeps every triangle from folding over.
TEST(CurvatureAccuracy, JitteredMeshesStayBounded) {
  const Errors sphere = relative_errors(make_icosphere(5, 1.0, {0.2, 7}));
  EXPECT_LT(sphere.gaussian, 0.05);
  EXPECT_LT(sphere.mean, 0.05);
  const Errors wave = relative_errors(make_wave_field(129, 0.1, 6.0, 1.0, {0.2, 7}));
  EXPECT_LT(wave.gaussian, 0.2);
  EXPECT_LT(wave.mean, 0.5);
  const Errors saddle = relative_errors(make_saddle(129, 0.5, {0.2, 7}));
  EXPECT_LT(saddle.gaussian, 0.2);
  EXPECT_TRUE(std::isfinite(saddle.mean));
}

TEST(CurvatureAccuracy, SphereSignFollowsWinding) {
  AnalyticSurface s = make_icosphere(3);
  for (Triangle& t : s.mesh.triangles) std::swap(t[1], t[2]);  // inward winding
  const Curvature c = curvature_of(s.mesh);
  EXPECT_EQ(c.flipped, 0u);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    EXPECT_NEAR(c.field.mean[v], -1.0, 1e-2);
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 2e-2);  // K does not depend on the orientation
    EXPECT_LT(c.field.normal[v].dot(s.mesh.positions[v]), 0.0);
  }
}

}  // namespace
}  // namespace toonwater::test
