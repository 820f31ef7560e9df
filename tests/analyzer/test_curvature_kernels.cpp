// The curvature gather's AVX2 and FMA instantiation against the portable one: same statuses and
// counts, values equal up to round-off, on regular, jittered and thin-faced meshes (the last
// through the intrinsic Delaunay pass). Skipped where the processor has no AVX2 and FMA. And the
// gather on faces in any order: a vertex whose faces lie in several chunks of the face pass gets
// the values of the faces in order, up to round-off.
#include "tests/analyzer/curvature_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace toonwater::test {
namespace {

// Fused multiply-adds round once where the portable path rounds twice: a few ulps per term,
// and a one-ring sums about twenty of them. Differences are measured against the mesh's
// curvature scale c (the largest |H|): K to within this fraction of c², H and the areas
// relative to c and the largest area. k1,2 = H ± sqrt(H² − K) amplify a difference δ in H² − K
// to sqrt(δ) where H² ≈ K (umbilics), so they get the square root of the fraction.
constexpr double round_off_tolerance = 1e-9;

double largest_magnitude(const std::vector<double>& values) {
  double largest = 0.0;
  for (double x : values) largest = std::max(largest, std::abs(x));
  return largest;
}

void expect_close(const std::vector<double>& expected, const std::vector<double>& actual,
                  double tolerance, const char* what) {
  for (std::size_t v = 0; v < expected.size(); ++v)
    ASSERT_NEAR(actual[v], expected[v], tolerance) << what << " at vertex " << v;
}

// The same statuses, and values equal up to round-off.
void expect_fields_agree(const CurvatureField& expected, const CurvatureField& actual) {
  ASSERT_TRUE(all_finite(actual));
  EXPECT_EQ(actual.status, expected.status);
  const double c = largest_magnitude(expected.mean);
  ASSERT_GT(c, 0.0);
  expect_close(expected.area, actual.area, round_off_tolerance * largest_magnitude(expected.area),
               "area");
  expect_close(expected.gaussian, actual.gaussian, round_off_tolerance * c * c, "K");
  expect_close(expected.mean, actual.mean, round_off_tolerance * c, "H");
  for (std::size_t v = 0; v < expected.normal.size(); ++v)
    ASSERT_LT((actual.normal[v] - expected.normal[v]).norm(), round_off_tolerance) << v;
}

void expect_kernels_agree(TriangleMesh mesh) {
  if (!avx2_fma_supported()) GTEST_SKIP() << "this processor has no AVX2 and FMA";
  const MeshTopology topology = analyze_topology(mesh);
  orient_consistently(mesh, topology);
  const CurvatureField portable = compute_curvature(mesh, topology, CurvatureKernel::portable);
  const CurvatureField fused = compute_curvature(mesh, topology, CurvatureKernel::avx2_fma);
  EXPECT_EQ(fused.degenerate_faces, portable.degenerate_faces);
  EXPECT_EQ(fused.mollified_faces, portable.mollified_faces);
  EXPECT_EQ(fused.cap_faces, portable.cap_faces);
  EXPECT_EQ(fused.intrinsic_flips, portable.intrinsic_flips);
  expect_fields_agree(portable, fused);
}

TEST(CurvatureKernels, AgreeOnAnIcosphere) { expect_kernels_agree(make_icosphere(5).mesh); }

TEST(CurvatureKernels, AgreeOnAJitteredWaveField) {
  // Large enough to split over the cores.
  expect_kernels_agree(make_wave_field(240, 0.1, 6.0, 1.0, {0.3, 7}).mesh);
}

TEST(CurvatureKernels, AgreeOnACylinderWithACapAndOnAUvSphere) {
  // A boundary and a collinear cap, which takes the mollified intrinsic Delaunay pass; the UV
  // sphere's poles are fans of thin faces.
  TriangleMesh m = make_cylinder(64, 32, 1.0, 2.0).mesh;
  insert_t_junction(m, m.triangles[40][0], m.triangles[40][1], Vec3(0.0, 0.0, 1e-9));
  const CurvatureField field = compute_curvature(m, analyze_topology(m));
  EXPECT_GT(field.mollified_faces + field.cap_faces, 0u) << "the intrinsic pass is not exercised";
  expect_kernels_agree(std::move(m));
  TriangleMesh uv = make_uv_sphere(71, 142).mesh;
  expect_kernels_agree(std::move(uv));
}

// With its faces shuffled, nearly every vertex of a mesh large enough to split over the cores
// has faces in more than one chunk of the face pass, and is summed again by the vertex pass:
// the values are those of the faces in order, up to the round-off of the other order of the
// terms (both with the fastest kernel).
TEST(CurvatureGather, SumsVerticesWithFacesInSeveralChunksAsTheOthers) {
  const TriangleMesh in_order = make_wave_field(240, 0.1, 6.0, 1.0, {0.3, 7}).mesh;
  TriangleMesh shuffled = in_order;
  std::mt19937 rng(12);
  std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
  expect_fields_agree(compute_curvature(in_order, analyze_topology(in_order)),
                      compute_curvature(shuffled, analyze_topology(shuffled)));
}

}  // namespace
}  // namespace toonwater::test
