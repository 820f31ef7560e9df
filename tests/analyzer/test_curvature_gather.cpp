// The curvature gather on faces in any order: a vertex whose faces lie in several chunks of the
// face pass gets the values of the faces in order, up to round-off.
#include "tests/analyzer/curvature_test_util.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace toonwater::test {
namespace {

// The other order of the terms changes a one-ring's sums (about twenty terms) by a few ulps.
// Differences are measured against the mesh's curvature scale c (the largest |H|): K to within
// this fraction of c², H and the areas relative to c and the largest area (k1 and k2 follow from
// K and H).
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

// With its faces shuffled, nearly every vertex of a mesh large enough to split over the cores
// has faces in more than one chunk of the face pass, and is summed again by the vertex pass:
// the values are those of the faces in order, up to the round-off of the other order of the
// terms.
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
