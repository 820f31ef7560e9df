// Stability of the curvature estimators. One suite runs over estimator × mesh corpus — analytic
// surfaces, stiff constructed cases (collinear faces, repeated corners, caps and needles within
// 1e-4° of 180° and 0°, non-manifold and isolated vertices), the fuzz corpus and, when
// ../shared/data is present, real simulation frames — and asserts what must hold on every
// mesh: finite values, k1 ≥ k2, status counts, K ∝ 1/s² and H ∝ 1/s, invariance under rotation
// and translation; and Gauss–Bonnet on the closed ones. Then the values of the one-ring
// estimator on the stiff cases (the jet's are in test_curvature_jet.cpp).
#include "analyzer/mesh_reader.hpp"
#include "analyzer/weld.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>
#include <optional>
#include <set>

namespace toonwater::test {
namespace {

// ---- The corpus ----

// An icosphere with a T-junction on one edge whose new vertex stands 1e-8 of the edge off the
// midpoint: a cap within 1e-4° of 180° and two needles below 1e-4°.
TriangleMesh sphere_with_cap() {
  TriangleMesh m = make_icosphere(4).mesh;
  const Triangle t0 = m.triangles[0];
  const Vec3 a = m.positions[t0[0]], b = m.positions[t0[1]];
  insert_t_junction(m, t0[0], t0[1], 1e-8 * (b - a).norm() * (0.5 * (a + b)).normalized());
  return m;
}

// A flat grid with a collinear cap (an exact T-junction) in the middle.
TriangleMesh plane_with_collinear_cap() {
  TriangleMesh m = plane(9);
  insert_t_junction(m, 4 * 9 + 4, 5 * 9 + 4, Vec3::Zero());
  return m;
}

TriangleMesh plane_with_repeated_corners() {
  TriangleMesh m = plane(5);
  m.triangles.push_back({6, 6, 7});        // repeated corner
  m.positions.push_back(m.positions[12]);  // a coincident copy of the centre vertex
  m.triangles.push_back({12, 25, 13});     // zero-length edge 12–25
  return m;
}

// A low convex cone whose apex sits just inside one edge of its hexagonal base: the face on
// that edge has an angle of about 170° at the apex.
TriangleMesh obtuse_cone() {
  TriangleMesh m;
  const int ring = 6;
  for (int i = 0; i < ring; ++i) {
    const double phi = 2.0 * std::numbers::pi * i / ring;
    m.positions.emplace_back(std::cos(phi), std::sin(phi), 0.0);
  }
  m.positions.push_back(0.9495 * 0.5 * (m.positions[0] + m.positions[1]) + Vec3(0, 0, 0.001));
  for (int i = 0; i < ring; ++i) m.triangles.push_back({ring, i, (i + 1) % ring});
  return m;
}

// Two spheres touching at one vertex (a bow tie of fans), and a fin: a third face on an edge.
TriangleMesh touching_spheres_with_fin() {
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
  return m;
}

TriangleMesh with_isolated_vertex() {
  TriangleMesh m = make_icosphere(2).mesh;
  m.positions.emplace_back(5, 5, 5);
  return m;
}

TriangleMesh single_triangle() {
  TriangleMesh m;
  m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}};
  return m;
}

TriangleMesh sheared_plane() {
  TriangleMesh m = plane(33);
  for (Vec3& p : m.positions) p = Vec3(p.x() * 3.0 + 0.1 * p.y(), p.y() * 0.5, 0.0);
  return m;
}

// A fan of `faces` triangles round a centre vertex whose ring zig-zags up and down by
// `height`: each corner at the centre is near 90°, so the angle sum makes many whole turns.
TriangleMesh zig_zag_fan(int faces, double height) {
  TriangleMesh m;
  m.positions.emplace_back(0.0, 0.0, 0.0);
  for (int k = 0; k < faces; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / faces;
    m.positions.emplace_back(std::cos(phi), std::sin(phi), k % 2 == 0 ? height : -height);
  }
  for (int k = 0; k < faces; ++k) m.triangles.push_back({0, 1 + k, 1 + (k + 1) % faces});
  return m;
}

std::optional<TriangleMesh> read_welded(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) return std::nullopt;
  return weld_coincident_vertices(read_mesh(path).mesh).mesh;
}

struct CorpusMesh {
  std::string name;
  std::function<std::optional<TriangleMesh>()> make;  // nullopt: data absent
  // Closed and manifold, no face without shape: every vertex must be computed.
  bool closed = false;
  // How much more than a smooth mesh the results amplify the rounding of transformed input:
  // for both estimators, and in addition for the jet.
  double amplification = 1.0;
  double jet_amplification = 1.0;
  // Features below the rounding of its largest coordinates: a rotation or translation changes
  // its shape, so only finiteness and statuses are compared.
  bool features_below_rounding = false;
};

std::vector<CorpusMesh> corpus() {
  auto fixed = [](TriangleMesh (*f)()) {
    return [f]() -> std::optional<TriangleMesh> { return f(); };
  };
  auto analytic = [](std::function<AnalyticSurface()> f) {
    return [f]() -> std::optional<TriangleMesh> { return f().mesh; };
  };
  std::vector<CorpusMesh> meshes = {
      {"icosphere", analytic([] { return make_icosphere(3); }), true},
      {"uv_sphere", analytic([] { return make_uv_sphere(24, 48); }), true},
      // 10k vertices, pole fans of 2.5°.
      {"uv_sphere_10k", analytic([] { return make_uv_sphere(71, 142); }), true},
      {"torus", analytic([] { return make_torus(48, 24); }), true},
      {"ellipsoid", analytic([] { return make_ellipsoid(3); }), true},
      {"jittered_icosphere", analytic([] {
         return make_icosphere(3, 1.0, {0.2, 7});
       }),
       true},
      {"cylinder", analytic([] { return make_cylinder(32, 16); })},
      {"saddle", analytic([] { return make_saddle(33); })},
      {"wave", analytic([] { return make_wave_field(33); })},
      // The cap's height is 1e-8 of its length: rounding moves it by 1e-8 relative.
      {"sphere_with_cap", fixed(sphere_with_cap), true, 10.0},
      {"plane_with_collinear_cap", fixed(plane_with_collinear_cap)},
      {"plane_with_repeated_corners", fixed(plane_with_repeated_corners)},
      {"obtuse_cone", fixed(obtuse_cone)},
      {"touching_spheres_with_fin", fixed(touching_spheres_with_fin)},
      {"isolated_vertex", fixed(with_isolated_vertex)},
      {"single_triangle", fixed(single_triangle)},
      {"sheared_plane", fixed(sheared_plane)},
      // A hub of 100,002 faces: past the one-ring estimator's turn count and the jet's growth
      // limit (each neighbour's two-ring would hold the whole fan: over a minute, not
      // milliseconds).
      {"hub_fan_100k", [] { return std::optional<TriangleMesh>(zig_zag_fan(100002, 1e-3)); }},
  };
  const std::filesystem::path fuzz = TOONWATER_FUZZ_CORPUS;
  for (const char* dir : {"analyze", "obj", "off", "ply", "stl", "bobj"}) {
    std::set<std::filesystem::path> files;  // sorted: stable test names
    for (const auto& entry : std::filesystem::directory_iterator(fuzz / dir))
      files.insert(entry.path());
    for (const auto& path : files) {
      const std::string name = std::string("fuzz_") + dir + "_" + path.stem().stem().string();
      // slivers.obj: a 1e-12 offset beside a coordinate of 1e6.
      meshes.push_back({name, [path] { return read_welded(path); }, false, 1.0, 1.0,
                        name == "fuzz_analyze_slivers"});
    }
  }
  for (const char* frame : {"mantaflow-wake/water_0001.obj", "mantaflow-wake/water_0030.obj",
                            "blender-ocean/water_0001.obj"}) {
    std::string name = frame;
    std::replace_if(
        name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
    // Marching-cubes slivers give the jet near-singular neighbourhoods: it accepts fits down to
    // a pivot ratio of 1e-12, whose solutions amplify rounding by up to that much more.
    meshes.push_back({"real_" + name,
                      [frame]() -> std::optional<TriangleMesh> {
                        const std::filesystem::path shared = shared_dir();
                        if (shared.empty()) return std::nullopt;
                        return read_welded(shared / "data" / frame);
                      },
                      std::string(frame).starts_with("mantaflow"), 1.0, 1e4});
  }
  return meshes;
}

const std::vector<CorpusMesh>& the_corpus() {
  static const std::vector<CorpusMesh> meshes = corpus();
  return meshes;
}

// ---- Laws over estimator × corpus ----

bool has_no_shape(const TriangleMesh& m, const Triangle& t) {
  return t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || m.positions[t[0]] == m.positions[t[1]] ||
         m.positions[t[1]] == m.positions[t[2]] || m.positions[t[2]] == m.positions[t[0]];
}

double rms_of(const std::vector<double>& values) {
  double sum = 0.0;
  for (double x : values) sum += x * x;
  return values.empty() ? 0.0 : std::sqrt(sum / static_cast<double>(values.size()));
}

// K and H agree within `tolerance` of |value| + the field's scale: relative where a value is
// typical, absolute where it passes through zero. The scale of K is RMS(K) + RMS(H)² + 1/size²,
// of H RMS(H) + sqrt(RMS(K)) + 1/size, with `size` the mesh's extent: a cylinder's K is zero but
// its H is not, a plane's are both round-off.
void expect_close_fields(const CurvatureField& actual, const CurvatureField& expected,
                         double tolerance, double size, double length_scale = 1.0) {
  const double rms_k = rms_of(expected.gaussian), rms_h = rms_of(expected.mean);
  const double scale_k = rms_k + rms_h * rms_h + 1.0 / (size * size);
  const double scale_h = rms_h + std::sqrt(rms_k) + 1.0 / size;
  ASSERT_EQ(actual.gaussian.size(), expected.gaussian.size());
  std::size_t reported = 0;
  for (std::size_t v = 0; v < expected.gaussian.size(); ++v) {
    const double k = actual.gaussian[v] * length_scale * length_scale;
    const double h = actual.mean[v] * length_scale;
    const bool k_close = std::abs(k - expected.gaussian[v]) <=
                         tolerance * (std::abs(expected.gaussian[v]) + scale_k);
    const bool h_close =
        std::abs(h - expected.mean[v]) <= tolerance * (std::abs(expected.mean[v]) + scale_h);
    if ((!k_close || !h_close) && reported++ < 5)
      ADD_FAILURE() << "vertex " << v << ": K " << k << " vs " << expected.gaussian[v] << ", H "
                    << h << " vs " << expected.mean[v];
  }
}

class CurvatureStability : public testing::TestWithParam<std::tuple<Estimator, std::size_t>> {
 protected:
  void SetUp() override {
    const CorpusMesh& entry = the_corpus()[std::get<1>(GetParam())];
    std::optional<TriangleMesh> m = entry.make();
    if (!m) GTEST_SKIP() << "../shared/data is absent: " << entry.name << " skipped";
    mesh_ = std::move(*m);
    closed_ = entry.closed;
    amplification_ = entry.amplification *
                     (std::get<0>(GetParam()) == Estimator::jet ? entry.jet_amplification : 1.0);
    features_below_rounding_ = entry.features_below_rounding;
    reference_ = run(mesh_);
    Vec3 low = Vec3::Constant(std::numeric_limits<double>::max()), high = -low;
    for (const Vec3& p : mesh_.positions) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
    size_ = mesh_.positions.empty() ? 1.0 : std::max((high - low).maxCoeff(), 1e-300);
  }
  Curvature run(const TriangleMesh& m) const { return curvature_of(m, std::get<0>(GetParam())); }

  TriangleMesh mesh_;
  bool closed_ = false;
  double size_ = 1.0;  // the mesh's extent
  double amplification_ = 1.0;
  bool features_below_rounding_ = false;
  Curvature reference_;
};

TEST_P(CurvatureStability, FiniteOrderedAndCounted) {
  const CurvatureField& f = reference_.field;
  ASSERT_TRUE(all_finite(f));
  for (std::size_t v = 0; v < f.mean.size(); ++v)
    EXPECT_GE(principal(f, v).k1, principal(f, v).k2) << v;
  const auto count = [&](CurvatureStatus s) {
    return static_cast<std::size_t>(std::count(f.status.begin(), f.status.end(), s));
  };
  EXPECT_EQ(f.extrapolated_vertices, count(CurvatureStatus::extrapolated));
  EXPECT_EQ(f.undefined_vertices, count(CurvatureStatus::undefined));
  for (std::size_t v = 0; v < f.status.size(); ++v)
    if (f.status[v] == CurvatureStatus::undefined) {
      EXPECT_EQ(f.gaussian[v], 0.0);
      EXPECT_EQ(f.mean[v], 0.0);
    }
  if (closed_) {
    EXPECT_EQ(f.extrapolated_vertices, 0u);
    EXPECT_EQ(f.undefined_vertices, 0u);
  }
  if (std::get<0>(GetParam()) != Estimator::one_ring) return;
  // The one-ring estimator computes every interior vertex that no shapeless face touches, up
  // to 100,000 faces a vertex (the most whose whole turns it counts: curvature.cpp).
  std::vector<bool> at_shapeless(mesh_.positions.size(), false);
  std::size_t shapeless = 0;
  for (const Triangle& t : reference_.mesh.triangles)
    if (has_no_shape(reference_.mesh, t)) {
      ++shapeless;
      for (std::int32_t v : t) at_shapeless[v] = true;
    }
  EXPECT_EQ(f.degenerate_faces, shapeless);
  for (std::size_t v = 0; v < f.status.size(); ++v)
    if (reference_.topology.kind[v] == VertexKind::interior && !at_shapeless[v] &&
        f.area[v] > 0.0 &&
        reference_.topology.vertex_faces.of(static_cast<std::int32_t>(v)).size() <= 100000) {
      EXPECT_EQ(f.status[v], CurvatureStatus::computed) << v;
    }
}

TEST_P(CurvatureStability, ScalesAsInverseLength) {
  // Powers of two are exact; other factors leave the rounding of the scaled input, amplified
  // by the size-to-edge ratio in the second differences.
  for (double scale : {0x1p-400, 0x1p+400, 1e-150, 1e150, 1e-6, 1e6}) {
    SCOPED_TRACE(scale);
    TriangleMesh scaled = mesh_;
    for (Vec3& p : scaled.positions) p *= scale;
    const Curvature c = run(scaled);
    ASSERT_TRUE(all_finite(c.field));
    EXPECT_EQ(c.field.status, reference_.field.status);
    if (std::ilogb(scale) == std::log2(scale) && std::get<0>(GetParam()) == Estimator::one_ring) {
      // Exactly: the estimator rescales by a power of two itself.
      std::vector<double> k = c.field.gaussian, h = c.field.mean;
      for (double& x : k) x *= scale * scale;
      for (double& x : h) x *= scale;
      EXPECT_EQ(k, reference_.field.gaussian);
      EXPECT_EQ(h, reference_.field.mean);
    } else {
      expect_close_fields(c.field, reference_.field, 1e-9 * amplification_, size_, scale);
    }
  }
}

TEST_P(CurvatureStability, InvariantUnderRotation) {
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  TriangleMesh rotated = mesh_;
  for (Vec3& p : rotated.positions) p = rotation * p;
  const Curvature c = run(rotated);
  ASSERT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.status, reference_.field.status);
  if (!features_below_rounding_)
    expect_close_fields(c.field, reference_.field, 1e-9 * amplification_, size_);
}

TEST_P(CurvatureStability, InvariantUnderTranslation) {
  // An offset of 1000 times the mesh's extent costs the coordinates about 10 of their 53 bits.
  const double extent = size_;
  TriangleMesh moved = mesh_;
  for (Vec3& p : moved.positions) p += 1e3 * extent * Vec3(1, -1, 1);
  const Curvature c = run(moved);
  ASSERT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.status, reference_.field.status);
  if (!features_below_rounding_)
    expect_close_fields(c.field, reference_.field, 1e-6 * amplification_, size_);
}

std::string parameter_name(const testing::TestParamInfo<CurvatureStability::ParamType>& info) {
  return std::string(std::get<0>(info.param) == Estimator::one_ring ? "one_ring_" : "jet_") +
         the_corpus()[std::get<1>(info.param)].name;
}

INSTANTIATE_TEST_SUITE_P(Corpus, CurvatureStability,
                         testing::Combine(testing::Values(Estimator::one_ring, Estimator::jet),
                                          testing::Range<std::size_t>(0, the_corpus().size())),
                         parameter_name);

// Σ K·A = Σ (2π − Σθ) = 2πV − πF = 2πχ on every closed manifold mesh of the corpus, with the
// one-ring estimator (an angle-deficit law): each vertex must have its own one-ring.
TEST(CurvatureGaussBonnet, HoldsOnTheClosedMeshesOfTheCorpus) {
  std::size_t checked = 0;
  for (const CorpusMesh& entry : the_corpus()) {
    const std::optional<TriangleMesh> m = entry.make();
    if (!m) continue;
    const Curvature c = curvature_of(*m);
    const bool closed_manifold =
        !m->positions.empty() && c.field.degenerate_faces == 0 &&
        std::all_of(c.topology.kind.begin(), c.topology.kind.end(),
                    [](VertexKind k) { return k == VertexKind::interior; });
    if (!closed_manifold) continue;
    SCOPED_TRACE(entry.name);
    ++checked;
    EXPECT_EQ(c.field.extrapolated_vertices + c.field.undefined_vertices, 0u);
    std::set<std::pair<std::int32_t, std::int32_t>> edges;
    for (const Triangle& t : c.mesh.triangles)
      for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
    const double euler = static_cast<double>(m->positions.size()) -
                         static_cast<double>(edges.size()) +
                         static_cast<double>(c.mesh.triangles.size());
    double total = 0.0, magnitude = 0.0;
    for (std::size_t v = 0; v < c.field.gaussian.size(); ++v) {
      total += c.field.gaussian[v] * c.field.area[v];
      magnitude += std::abs(c.field.gaussian[v] * c.field.area[v]);
    }
    EXPECT_NEAR(total, 2.0 * std::numbers::pi * euler,
                1e-10 * std::max(2.0 * std::numbers::pi * std::abs(euler), magnitude));
  }
  // Icospheres, UV spheres, torus, ellipsoid, the capped sphere, the tetrahedra; the frames.
  EXPECT_GE(checked, 11u);
}

// ---- Values of the one-ring estimator on the stiff cases ----

TEST(CurvatureStiffCases, CollinearFaceInAPlaneKeepsKAndHZero) {
  const TriangleMesh m = plane_with_collinear_cap();
  const Curvature c = curvature_of(m);
  EXPECT_EQ(c.field.degenerate_faces, 0u);
  EXPECT_EQ(c.field.mollified_faces, 1u);
  EXPECT_GT(c.field.mollification, 0.0);
  EXPECT_LT(c.field.mollification, 1e-5);  // ε of the cap's length
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (c.topology.kind[v] != VertexKind::interior) continue;
    EXPECT_EQ(c.field.status[v], CurvatureStatus::computed) << v;
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12) << v;
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12) << v;
  }
}

TEST(CurvatureStiffCases, CapsAndNeedlesBelowATenThousandthOfADegreeOnASphere) {
  const TriangleMesh m = sphere_with_cap();
  const Curvature c = curvature_of(m);
  EXPECT_EQ(c.field.degenerate_faces, 0u);
  EXPECT_EQ(c.field.mollified_faces, 1u);
  const Triangle cap = m.triangles.back();
  const Vec3 u = m.positions[cap[0]] - m.positions[cap[2]],
             w = m.positions[cap[1]] - m.positions[cap[2]];
  const double cap_angle = std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi;
  EXPECT_GT(cap_angle, 180.0 - 1e-4);
  EXPECT_LT(cap_angle, 180.0);
  // Every vertex keeps its own one-ring, the cap's corners included. The new vertex m is a
  // point on the crease along the old edge: its angles sum to 2π (K = 0, exactly as the
  // piecewise-linear surface has it), and the old edge's ends keep their deficits on a smaller
  // area. Nowhere a spike: standing on edge, the cap would make the cotangent Laplacian see a
  // 90° crease along its long edge (MeshLab: H = 1e7 next to such a face).
  const Curvature before = curvature_of(make_icosphere(4).mesh);
  const std::int32_t a = cap[0], b = cap[1], added = cap[2];
  double deficit_before = 0.0, deficit_after = 0.0;
  for (std::int32_t v : {a, b}) deficit_before += before.field.gaussian[v] * before.field.area[v];
  for (std::int32_t v : {a, b, added}) deficit_after += c.field.gaussian[v] * c.field.area[v];
  EXPECT_NEAR(deficit_after, deficit_before, 1e-9 * deficit_before);
  EXPECT_NEAR(c.field.gaussian[added], 0.0, 1e-4);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_EQ(c.field.status[v], CurvatureStatus::computed) << v;
    const bool at_cap = v == static_cast<std::size_t>(a) || v == static_cast<std::size_t>(b) ||
                        v == static_cast<std::size_t>(added);
    EXPECT_NEAR(c.field.mean[v], 1.0, at_cap ? 0.7 : 0.05) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, at_cap ? 1.0 : 0.1) << v;
  }
}

TEST(CurvatureStiffCases, ThinPoleFansOfAUvSphereKeepTheirGeometry) {
  // 2.5° at the poles: exact geometry, not round-off.
  const AnalyticSurface s = make_uv_sphere(71, 142);
  const Curvature c = curvature_of(s.mesh);
  EXPECT_EQ(c.field.degenerate_faces, 0u);
  EXPECT_EQ(c.field.mollified_faces, 0u);
  EXPECT_EQ(c.field.extrapolated_vertices, 0u);
  EXPECT_EQ(c.field.undefined_vertices, 0u);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    EXPECT_NEAR(c.field.mean[v], 1.0, 2e-3) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 2e-2) << v;
  }
}

TEST(CurvatureStiffCases, ObtuseTrianglesNearOneEightyDegrees) {
  // Meyer's rule gives the apex half of the area of the face with the 170° angle.
  const TriangleMesh m = obtuse_cone();
  const std::int32_t apex = 6;
  const Curvature c = curvature_of(m);
  ASSERT_TRUE(all_finite(c.field));
  const Vec3 u = m.positions[0] - m.positions[apex], w = m.positions[1] - m.positions[apex];
  EXPECT_GT(std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / std::numbers::pi, 169.0);
  EXPECT_EQ(c.field.mollified_faces, 0u);
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
    const bool obtuse_elsewhere =
        (m.positions[apex] - m.positions[t[1]]).dot(m.positions[t[2]] - m.positions[t[1]]) < 0.0 ||
        (m.positions[apex] - m.positions[t[2]]).dot(m.positions[t[1]] - m.positions[t[2]]) < 0.0;
    if (obtuse_at_apex)
      expected_area += face_area / 2;
    else if (obtuse_elsewhere)
      expected_area += face_area / 4;
    else {
      const double cot_1 =
          (m.positions[apex] - m.positions[t[1]]).dot(m.positions[t[2]] - m.positions[t[1]]) /
          (2 * face_area);
      const double cot_2 =
          (m.positions[apex] - m.positions[t[2]]).dot(m.positions[t[1]] - m.positions[t[2]]) /
          (2 * face_area);
      expected_area += (b.squaredNorm() * cot_1 + a.squaredNorm() * cot_2) / 8;
    }
  }
  // ...so K and the area follow Meyer's obtuse rules exactly.
  EXPECT_NEAR(c.field.area[apex], expected_area, 1e-15);
  EXPECT_NEAR(c.field.gaussian[apex], (2.0 * std::numbers::pi - angle_sum) / expected_area, 1e-9);
  EXPECT_GT(c.field.gaussian[apex], 0.0);  // a convex cone
  EXPECT_GT(c.field.mean[apex], 0.0);
}

TEST(CurvatureStiffCases, RepeatedCornersAndZeroLengthEdgesAreLeftOut) {
  const TriangleMesh m = plane_with_repeated_corners();
  const Curvature c = curvature_of(m);
  EXPECT_TRUE(all_finite(c.field));
  EXPECT_EQ(c.field.degenerate_faces, 2u);
  EXPECT_NEAR(c.field.gaussian[6], 0.0, 1e-12);
  EXPECT_EQ(c.field.status[25], CurvatureStatus::undefined);
}

TEST(CurvatureStiffCases, BoundaryVerticesTakeTheirNeighboursMean) {
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

TEST(CurvatureStiffCases, IsolatedVertexIsUndefinedAndCounted) {
  const Curvature c = curvature_of(with_isolated_vertex());
  EXPECT_EQ(c.topology.isolated_vertices, 1u);
  EXPECT_EQ(c.field.status.back(), CurvatureStatus::undefined);
  EXPECT_EQ(c.field.undefined_vertices, 1u);
  EXPECT_EQ(c.field.gaussian.back(), 0.0);
}

TEST(CurvatureStiffCases, NonManifoldVertexAndEdge) {
  const TriangleMesh m = touching_spheres_with_fin();
  const Curvature c = curvature_of(m);
  const std::int32_t fin_corner = m.triangles[5][0];
  EXPECT_EQ(c.topology.kind[0], VertexKind::nonmanifold);
  EXPECT_EQ(c.topology.kind[fin_corner], VertexKind::nonmanifold);
  EXPECT_EQ(c.topology.nonmanifold_edges, 1u);
  EXPECT_EQ(c.field.status[0], CurvatureStatus::extrapolated);
  EXPECT_GT(c.field.mean[0], 0.5);  // the spheres' curvature, not an angle sum of 4π
  EXPECT_EQ(count_components(c.mesh, c.topology), 1u);
}

TEST(CurvatureStiffCases, SingleTriangleAndEmptyMesh) {
  const Curvature c = curvature_of(single_triangle());
  EXPECT_EQ(c.topology.boundary_vertices, 3u);
  EXPECT_EQ(c.field.undefined_vertices, 3u);  // no vertex has a computed neighbour
  EXPECT_NEAR(c.field.area[0] + c.field.area[1] + c.field.area[2], 0.5, 1e-15);

  const Curvature empty = curvature_of(TriangleMesh{});
  EXPECT_TRUE(empty.field.gaussian.empty());
  EXPECT_EQ(count_components(empty.mesh, empty.topology), 0u);
}

TEST(CurvatureStiffCases, AngleSumOfHundredsOfTurnsIsExact) {
  // 1000 corners of about 90°: 250 turns, and a turn product whose magnitude is brought back
  // several times (curvature.cpp); K from the angle sum summed here corner by corner.
  const TriangleMesh m = zig_zag_fan(1000, 1.0);
  const Curvature c = curvature_of(m);
  ASSERT_EQ(c.field.status[0], CurvatureStatus::computed);
  double angle_sum = 0.0;
  for (const Triangle& t : m.triangles) {
    const Vec3 u = m.positions[t[1]] - m.positions[t[0]], v = m.positions[t[2]] - m.positions[t[0]];
    angle_sum += std::atan2(u.cross(v).norm(), u.dot(v));
  }
  EXPECT_GT(angle_sum, 400.0 * std::numbers::pi);
  const double expected = (2.0 * std::numbers::pi - angle_sum) / c.field.area[0];
  EXPECT_NEAR(c.field.gaussian[0], expected, 1e-12 * std::abs(expected));
}

TEST(CurvatureStiffCases, VertexOfMoreThanAHundredThousandFacesIsLeftToItsNeighbours) {
  // Beyond what the turn count resolves (curvature.cpp): not computed, never wrong.
  const Curvature c = curvature_of(zig_zag_fan(100002, 1e-3));
  EXPECT_NE(c.field.status[0], CurvatureStatus::computed);
  EXPECT_TRUE(all_finite(c.field));
}

TEST(CurvatureStiffCases, FlatPlaneIsZeroToRoundOff) {
  const TriangleMesh m = sheared_plane();
  const Curvature c = curvature_of(m);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-12);
    EXPECT_NEAR(c.field.mean[v], 0.0, 1e-12);
  }
}

TEST(CurvatureStiffCases, InconsistentWindingIsRepairedAndCounted) {
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

// The classification counts the two-face edges whose faces wind them alike, and the orientation
// search runs only where there are some: a consistent mesh has none, and reversing a single face
// of a closed one makes its three edges misoriented.
TEST(CurvatureStiffCases, MisorientedEdgesAreCountedAndOnlyTheyStartTheSearch) {
  AnalyticSurface s = make_icosphere(3);
  EXPECT_EQ(analyze_topology(s.mesh).misoriented_edges, 0u);
  const std::vector<Triangle> consistent = s.mesh.triangles;
  EXPECT_EQ(orient_consistently(s.mesh, analyze_topology(s.mesh)), 0u);
  EXPECT_EQ(s.mesh.triangles, consistent);

  std::swap(s.mesh.triangles[10][1], s.mesh.triangles[10][2]);
  const MeshTopology topology = analyze_topology(s.mesh);
  EXPECT_EQ(topology.misoriented_edges, 3u);
  EXPECT_EQ(orient_consistently(s.mesh, topology), 1u);
  EXPECT_EQ(s.mesh.triangles, consistent);
  EXPECT_EQ(analyze_topology(s.mesh).misoriented_edges, 0u);
}

}  // namespace
}  // namespace toonwater::test
