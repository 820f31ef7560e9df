// Smoothing of the curvature field (analyzer/curvature_smoothing.hpp).
#include "analyzer/curvature_smoothing.hpp"
#include "tests/analyzer/curvature_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace toonwater::test {
namespace {

constexpr Jitter jittered{0.2, 7};

TEST(CurvatureSmoothing, ZeroStepsChangeNothing) {
  const AnalyticSurface s = make_saddle(33, 0.5, jittered);
  Curvature c = curvature_of(s.mesh);
  const CurvatureField before = c.field;
  smooth_curvature(c.mesh, c.topology.vertex_faces, c.field, 0);
  EXPECT_EQ(c.field.gaussian, before.gaussian);
  EXPECT_EQ(c.field.mean, before.mean);
}

TEST(CurvatureSmoothing, DampsTheCotangentNoiseOnJitteredMeshes) {
  const AnalyticSurface s = make_saddle(129, 0.5, jittered);
  Curvature c = curvature_of(s.mesh);
  const double h_scale = rms(s.mean, s.interior), k_scale = rms(s.gaussian, s.interior);
  const double mean_before = rms_error(c.field.mean, s.mean, s.interior, h_scale);
  const double gaussian_before = rms_error(c.field.gaussian, s.gaussian, s.interior, k_scale);
  smooth_curvature(c.mesh, c.topology.vertex_faces, c.field, 2);
  const double mean_after = rms_error(c.field.mean, s.mean, s.interior, h_scale);
  const double gaussian_after = rms_error(c.field.gaussian, s.gaussian, s.interior, k_scale);
  EXPECT_LT(mean_after, mean_before / 4);
  EXPECT_LT(gaussian_after, gaussian_before / 2);
}

TEST(CurvatureSmoothing, KeepsAConstantFieldAndAPlane) {
  const AnalyticSurface s = make_cylinder(32, 16, 0.5, 2.0);
  Curvature c = curvature_of(s.mesh);
  smooth_curvature(c.mesh, c.topology.vertex_faces, c.field, 5);
  for (std::size_t v = 0; v < s.mesh.positions.size(); ++v) {
    EXPECT_NEAR(c.field.mean[v], 1.0, 1e-12);
    EXPECT_NEAR(c.field.gaussian[v], 0.0, 1e-9);
  }
}

TEST(CurvatureSmoothing, UndefinedVerticesNeitherChangeNorContribute) {
  TriangleMesh m = make_icosphere(2).mesh;
  m.positions.emplace_back(5, 5, 5);      // isolated
  m.positions.push_back(m.positions[3]);  // a copy of vertex 3, in one face with a zero-length edge
  const auto copy = static_cast<std::int32_t>(m.positions.size() - 1);
  m.triangles.push_back({3, copy, 4});
  Curvature c = curvature_of(m);
  ASSERT_EQ(c.field.status[copy], CurvatureStatus::undefined);
  c.field.gaussian[copy] = c.field.mean[copy] = 1e300;  // would dominate any mean it entered
  smooth_curvature(c.mesh, c.topology.vertex_faces, c.field, 3);
  EXPECT_EQ(c.field.gaussian.back(), 1e300);
  EXPECT_EQ(c.field.gaussian[m.positions.size() - 2], 0.0);
  for (std::size_t v = 0; v + 2 < m.positions.size(); ++v) {
    EXPECT_NEAR(c.field.mean[v], 1.0, 0.05) << v;
    EXPECT_NEAR(c.field.gaussian[v], 1.0, 0.1) << v;
  }
}

// The formula of the header, gathered over each vertex's faces in the order VertexFaces lists
// them, on one thread.
std::vector<double> gathered(const TriangleMesh& mesh, const VertexFaces& faces,
                             const std::vector<double>& area,
                             const std::vector<std::uint8_t>& member, std::vector<double> values,
                             int steps) {
  for (int step = 0; step < steps; ++step) {
    std::vector<double> next = values;
    for (std::size_t v = 0; v < values.size(); ++v) {
      if (!member[v]) continue;
      double weight = 0.0, weighted = 0.0;
      for (const std::int32_t f : faces.of(static_cast<std::int32_t>(v))) {
        const Triangle& t = mesh.triangles[f];
        auto w = [&](int c) { return member[t[c]] ? area[t[c]] : 0.0; };
        auto x = [&](int c) { return member[t[c]] ? area[t[c]] * values[t[c]] : 0.0; };
        weight += w(0) + w(1) + w(2);
        weighted += x(0) + x(1) + x(2);
      }
      if (weight > 0.0) next[v] = weighted / weight;
    }
    values = std::move(next);
  }
  return values;
}

// Bit for bit the gather, on a mesh that splits over several cores, with its faces in order
// (few vertices on the chunks' borders) and shuffled (most of them there), and members with
// holes; a face with a repeated corner is no face of its corners.
TEST(CurvatureSmoothing, EqualsTheGatherOverEachVertexsFaces) {
  std::mt19937 rng(4);
  for (const bool shuffled : {false, true}) {
    TriangleMesh mesh = make_saddle(301, 0.5, jittered).mesh;
    if (shuffled) std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
    mesh.triangles.push_back({5, 5, 900});
    const Curvature c = curvature_of(mesh);
    std::vector<std::uint8_t> member(mesh.positions.size());
    for (auto& m : member) m = rng() % 7 != 0;
    std::vector<double> values = c.field.mean;
    smooth_vertex_field(c.mesh, c.topology.vertex_faces, c.field.area, member, values, 3);
    EXPECT_EQ(values,
              gathered(c.mesh, c.topology.vertex_faces, c.field.area, member, c.field.mean, 3))
        << (shuffled ? "shuffled faces" : "faces in order");
  }
}

// A vector field smoothed whole is each of its components smoothed alone, bit for bit.
TEST(CurvatureSmoothing, VectorsAreSmoothedAsTheirComponents) {
  std::mt19937 rng(9);
  TriangleMesh mesh = make_saddle(101, 0.5, jittered).mesh;
  std::shuffle(mesh.triangles.begin(), mesh.triangles.end(), rng);
  const Curvature c = curvature_of(mesh);
  std::vector<std::uint8_t> member(mesh.positions.size());
  for (auto& m : member) m = rng() % 5 != 0;
  std::vector<Vec3> vectors = c.field.normal;
  smooth_vertex_field(c.mesh, c.topology.vertex_faces, c.field.area, member, vectors, 7);
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> component(vectors.size());
    for (std::size_t v = 0; v < component.size(); ++v) component[v] = c.field.normal[v][axis];
    smooth_vertex_field(c.mesh, c.topology.vertex_faces, c.field.area, member, component, 7);
    for (std::size_t v = 0; v < component.size(); ++v)
      ASSERT_EQ(vectors[v][axis], component[v]) << "vertex " << v << ", axis " << axis;
  }
}

}  // namespace
}  // namespace toonwater::test
