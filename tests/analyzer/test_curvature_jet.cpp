// The jet estimator (analyzer/curvature_jet.hpp): accuracy on analytic surfaces, regular and
// jittered, against the one-ring operators; its own stiff cases (the laws and finiteness over
// the whole mesh corpus are in test_curvature_stability.cpp); selection through analyze_mesh
// and `toonwater analyze`.
//
// Errors are RMS over interior vertices relative to the RMS of the exact value (cylinder: K
// relative to H²), as in test_curvature_accuracy.cpp. "Jittered" moves every vertex by up to 0.2
// of the grid step within the surface, which keeps every triangle from folding over.
#include "analyzer/analysis.hpp"
#include "analyzer/curvature_jet.hpp"
#include "analyzer/obj_writer.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <functional>
#include <numbers>
#include <sstream>

namespace toonwater::test {
namespace {

constexpr Jitter jittered{0.2, 7};

Errors errors_of(const AnalyticSurface& s, const CurvatureField& field) {
  const double h_scale = rms(s.mean, s.interior);
  const double k_scale = rms(s.gaussian, s.interior);
  return {
      rms_error(field.gaussian, s.gaussian, s.interior, k_scale > 0 ? k_scale : h_scale * h_scale),
      rms_error(field.mean, s.mean, s.interior, h_scale)};
}

Errors jet_errors(const AnalyticSurface& s) { return errors_of(s, jet_of(s.mesh).field); }

// Error ratio between consecutive refinements (mesh spacing halved): about 4 for O(h²).
void expect_convergence(const std::vector<Errors>& errors, double min_ratio) {
  for (std::size_t i = 1; i < errors.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "refinement " << i);
    EXPECT_GT(errors[i - 1].gaussian / errors[i].gaussian, min_ratio);
    EXPECT_GT(errors[i - 1].mean / errors[i].mean, min_ratio);
  }
}

TEST(CurvatureJet, ConvergesQuadraticallyOnRegularMeshes) {
  std::vector<Errors> saddle, wave, torus, sphere;
  for (int n : {33, 65, 129}) saddle.push_back(jet_errors(make_saddle(n)));
  for (int n : {65, 129, 257}) wave.push_back(jet_errors(make_wave_field(n)));
  for (int n : {16, 32, 64}) torus.push_back(jet_errors(make_torus(2 * n, n)));
  for (int level = 3; level <= 5; ++level) sphere.push_back(jet_errors(make_icosphere(level, 2.0)));
  for (const auto* series : {&saddle, &wave, &torus, &sphere}) expect_convergence(*series, 3.5);
  EXPECT_LT(saddle.back().mean, 2e-3);
  EXPECT_LT(wave.back().mean, 3e-3);
  EXPECT_LT(torus.back().mean, 5e-2);
  EXPECT_LT(sphere.back().mean, 2e-2);
}

TEST(CurvatureJet, ConvergesQuadraticallyOnJitteredMeshes) {
  // Where the cotangent H stays near a constant error (see the next test), the fit keeps O(h²).
  std::vector<Errors> saddle, wave, sphere;
  for (int n : {33, 65, 129}) saddle.push_back(jet_errors(make_saddle(n, 0.5, jittered)));
  for (int n : {65, 129, 257})
    wave.push_back(jet_errors(make_wave_field(n, 0.1, 6.0, 1.0, jittered)));
  for (int level = 3; level <= 5; ++level)
    sphere.push_back(jet_errors(make_icosphere(level, 1.0, jittered)));
  for (const auto* series : {&saddle, &wave, &sphere}) expect_convergence(*series, 3.0);
}

// The requirement: on jittered triangulations of 10k vertices and more, at least 5× more
// accurate in H than the cotangent operator, and more accurate in K.
TEST(CurvatureJet,
     FiveTimesMoreAccurateInHThanTheCotangentOnJitteredMeshesFromTenThousandVertices) {
  struct Case {
    const char* name;
    std::function<AnalyticSurface(int)> make;  // at about 10k, then 40k vertices
  };
  const std::vector<Case> cases = {
      {"icosphere", [](int k) { return make_icosphere(5 + k, 1.0, jittered); }},
      {"ellipsoid", [](int k) { return make_ellipsoid(5 + k, 1.0, 0.8, 0.6, jittered); }},
      {"torus", [](int k) { return make_torus(144 << k, 72 << k, 1.0, 0.4, jittered); }},
      {"saddle", [](int k) { return make_saddle(101 << k, 0.5, jittered); }},
      {"wave field", [](int k) { return make_wave_field(101 << k, 0.1, 6.0, 1.0, jittered); }},
      {"cylinder", [](int k) { return make_cylinder(128 << k, 80 << k, 0.5, 2.0, jittered); }},
  };
  for (const Case& c : cases) {
    for (int k : {0, 1}) {
      const AnalyticSurface s = c.make(k);
      SCOPED_TRACE(testing::Message() << c.name << ", " << s.mesh.positions.size() << " vertices");
      ASSERT_GE(s.mesh.positions.size(), 10000u);
      const Errors cotangent = relative_errors(s);
      const Errors jet = jet_errors(s);
      EXPECT_LT(5.0 * jet.mean, cotangent.mean);
      EXPECT_LT(jet.gaussian, cotangent.gaussian);
    }
  }
}

TEST(CurvatureJet, SignsFollowTheNormals) {
  const AnalyticSurface saddle = make_saddle(65, 0.5, jittered);
  const Curvature c = jet_of(saddle.mesh);
  const std::size_t centre = 32 * 65 + 32;
  EXPECT_NEAR(c.field.gaussian[centre], -1.0, 1e-3);
  EXPECT_NEAR(c.field.mean[centre], 0.0, 1e-3);
  EXPECT_NEAR(principal(c.field, centre).k1, 1.0, 1e-3);
  EXPECT_NEAR(principal(c.field, centre).k2, -1.0, 1e-3);

  AnalyticSurface sphere = make_icosphere(4, 1.0, jittered);
  for (Triangle& t : sphere.mesh.triangles) std::swap(t[1], t[2]);  // inward winding
  const Curvature inward = jet_of(sphere.mesh);
  for (std::size_t v = 0; v < sphere.mesh.positions.size(); ++v) {
    EXPECT_NEAR(inward.field.mean[v], -1.0, 2e-2);
    EXPECT_NEAR(inward.field.gaussian[v], 1.0, 4e-2);
    EXPECT_LE(principal(inward.field, v).k2, principal(inward.field, v).k1);
  }
}

TEST(CurvatureJet, NormalsAndAreasAreTheOneRingEstimators) {
  const AnalyticSurface s = make_torus(48, 24, 1.0, 0.4, jittered);
  const Curvature one_ring = curvature_of(s.mesh), jet = jet_of(s.mesh);
  EXPECT_EQ(jet.field.area, one_ring.field.area);
  EXPECT_EQ(jet.field.normal, one_ring.field.normal);
  EXPECT_NE(jet.field.mean, one_ring.field.mean);
}

// ---- Stiff cases ----

TEST(CurvatureJetStability, CollinearCapAndZeroLengthEdgeInAPlaneKeepKAndHZero) {
  TriangleMesh m = plane(9);
  const std::int32_t centre = 4 * 9 + 4;
  const std::int32_t added = insert_t_junction(m, centre, centre + 9, Vec3::Zero());
  m.positions.push_back(m.positions[20]);  // a coincident copy: zero-length edges
  const auto copy = static_cast<std::int32_t>(m.positions.size() - 1);
  m.triangles.push_back({20, copy, 21});
  const Curvature c = jet_of(m);
  ASSERT_TRUE(all_finite(c.field));
  // The copy's only face has no shape, so it has no normal to fit in: undefined, as in the
  // one-ring estimator.
  EXPECT_EQ(c.field.status[copy], CurvatureStatus::undefined);
  EXPECT_EQ(c.field.undefined_vertices, 1u);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12) << v;
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12) << v;
  }
  // The cap's corners keep a fit of their own: slivers only contribute positions.
  EXPECT_EQ(c.field.status[added], CurvatureStatus::computed);
  EXPECT_EQ(c.field.status[centre], CurvatureStatus::computed);
}

TEST(CurvatureJetStability, CapsAndNeedlesBelowATenThousandthOfADegreeOnASphere) {
  AnalyticSurface s = make_icosphere(4);
  TriangleMesh& m = s.mesh;
  const Triangle t0 = m.triangles[0];
  const Vec3 a = m.positions[t0[0]], b = m.positions[t0[1]];
  insert_t_junction(m, t0[0], t0[1], 1e-8 * (b - a).norm() * (0.5 * (a + b)).normalized());
  const Curvature c = jet_of(m);
  ASSERT_TRUE(all_finite(c.field));
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_EQ(c.field.status[v], CurvatureStatus::computed) << v;
    EXPECT_NEAR(c.field.mean[v], 1.0, 0.05) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 0.1) << v;
  }
}

TEST(CurvatureJetStability, BoundaryVerticesAreFittedFromOneSide) {
  const AnalyticSurface s = make_cylinder(64, 32, 1.0, 2.0);
  const Curvature c = jet_of(s.mesh);
  EXPECT_EQ(c.topology.boundary_vertices, 128u);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    if (c.topology.kind[v] != VertexKind::boundary) continue;
    EXPECT_EQ(c.field.status[v], CurvatureStatus::computed);
    EXPECT_NEAR(c.field.mean[v], 0.5, 1e-2);  // a rim's one-ring angle sum would give ~0.25
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-2);
  }
}

TEST(CurvatureJetStability, IsolatedNonManifoldSingleTriangleAndEmpty) {
  // Two spheres touching at vertex 0, an isolated vertex.
  TriangleMesh m = make_icosphere(3).mesh;
  const auto n = static_cast<std::int32_t>(m.positions.size());
  const std::size_t face_count = m.triangles.size();
  const Vec3 apex = m.positions[0];
  for (std::int32_t v = 0; v < n; ++v) m.positions.push_back(2.0 * apex - m.positions[v]);
  for (std::size_t f = 0; f < face_count; ++f) {
    Triangle t = m.triangles[f];
    for (std::int32_t& v : t) v = v == 0 ? 0 : v + n;
    std::swap(t[1], t[2]);
    m.triangles.push_back(t);
  }
  m.positions.emplace_back(5, 5, 5);
  const Curvature c = jet_of(m);
  ASSERT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.topology.kind[0], VertexKind::nonmanifold);
  EXPECT_EQ(c.field.status[0], CurvatureStatus::extrapolated);
  EXPECT_EQ(c.field.extrapolated_vertices, 1u);
  // Isolated: the last vertex, and the second sphere's copy of vertex 0 (its faces use 0).
  EXPECT_EQ(c.field.status.back(), CurvatureStatus::undefined);
  EXPECT_EQ(c.field.status[n], CurvatureStatus::undefined);
  EXPECT_EQ(c.field.undefined_vertices, 2u);
  // Neighbours of the contact point do not fit the other sphere: every value stays the sphere's.
  for (std::size_t v = 0; v + 1 < m.positions.size(); ++v) {
    if (v == static_cast<std::size_t>(n)) continue;
    EXPECT_NEAR(c.field.mean[v], 1.0, 0.05) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 0.1) << v;
  }

  TriangleMesh tri;
  tri.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  tri.triangles = {{0, 1, 2}};
  const Curvature single = jet_of(tri);
  EXPECT_TRUE(all_finite(single.field));
  EXPECT_EQ(single.field.undefined_vertices, 3u);  // too few points for a fit, no fitted neighbour

  EXPECT_TRUE(jet_of(TriangleMesh{}).field.gaussian.empty());
}

TEST(CurvatureJetStability, ShearedPlaneIsZeroToRoundOff) {
  TriangleMesh m = plane(33);
  for (Vec3& p : m.positions) p = Vec3(p.x() * 3.0 + 0.1 * p.y(), p.y() * 0.5, 0.0);
  const Curvature c = jet_of(m);
  EXPECT_EQ(c.field.undefined_vertices, 0u);
  EXPECT_LE(c.field.extrapolated_vertices, 2u);  // corners in a single face: too few points
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12);
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12);
  }
}

// ---- Selection ----

TEST(CurvatureJet, SelectedThroughAnalyzeOptions) {
  const AnalyticSurface s = make_saddle(65, 0.5, jittered);
  AnalyzeOptions options;
  options.flow_regions = false;
  options.estimator = Estimator::jet;
  const Analysis a = analyze_mesh(s.mesh, options);
  const Curvature direct = jet_of(s.mesh);
  EXPECT_EQ(a.curvature.mean, direct.field.mean);
  EXPECT_EQ(a.curvature.gaussian, direct.field.gaussian);
}

std::vector<double> csv_column(const std::string& text, int column) {
  std::vector<double> values;
  std::istringstream lines(text);
  std::string line;
  std::getline(lines, line);  // header
  while (std::getline(lines, line)) {
    std::size_t start = 0;
    for (int i = 0; i < column; ++i) start = line.find(',', start) + 1;
    double value = 0.0;
    std::from_chars(line.data() + start, line.data() + line.size(), value);
    values.push_back(value);
  }
  return values;
}

TEST(CurvatureJet, AnalyzeCommandTakesEstimatorAndSmoothing) {
  const AnalyticSurface s = make_saddle(65, 0.5, jittered);
  ScratchDir dir;
  write_obj(dir / "saddle.obj", s.mesh);

  auto mean_error = [&](const std::vector<std::string>& options) {
    std::vector<std::string> args = {"analyze", (dir / "saddle.obj").string(), "--csv",
                                     (dir / "out.csv").string()};
    args.insert(args.end(), options.begin(), options.end());
    const CommandResult r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return rms_error(csv_column(read_text(dir / "out.csv"), 4), s.mean, s.interior, 1.0);
  };
  const double one_ring = mean_error({}), jet = mean_error({"--estimator", "jet"});
  const double smoothed = mean_error({"--smooth", "3"});
  EXPECT_LT(20.0 * jet, one_ring);
  EXPECT_LT(smoothed, 0.5 * one_ring);

  const CommandResult bad =
      run_toonwater({"analyze", (dir / "saddle.obj").string(), "--estimator", "tensor"});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("--estimator"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace toonwater::test
