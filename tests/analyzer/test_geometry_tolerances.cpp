// The named face predicates (analyzer/geometry_tolerances.hpp): degenerate is scale-free and
// catches collinear faces and NaN; shapeless is only a zero-length edge.
#include "analyzer/geometry_tolerances.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace toonwater {
namespace {

TEST(GeometryTolerances, DegenerateIsScaleFree) {
  // Within the scales whose squared areas double holds (coordinates within about 1e±75).
  for (double s : {1e-50, 1e-6, 1.0, 1e6, 1e50}) {
    EXPECT_FALSE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0, s, 0))) << s;
    // Height 1e-13 of the base: below the ratio at every scale.
    EXPECT_TRUE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0.5 * s, 1e-13 * s, 0)))
        << s;
    // Height 1e-11: a sliver, but a face with a plane.
    EXPECT_FALSE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(s, 0, 0), Vec3(0.5 * s, 1e-11 * s, 0)))
        << s;
  }
}

TEST(GeometryTolerances, RepeatedCornersCollinearAndNaNAreDegenerate) {
  EXPECT_TRUE(is_degenerate_triangle(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(0, 0, 1)));
  EXPECT_TRUE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(3, 3, 3)));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(is_degenerate_triangle(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(nan, 1, 0)));
  EXPECT_TRUE(is_degenerate_triangle(nan, 1.0));
}

TEST(GeometryTolerances, ShapelessIsAZeroLengthEdgeOnly) {
  EXPECT_TRUE(is_shapeless_triangle(0.0, 1.0, 1.0));
  EXPECT_TRUE(is_shapeless_triangle(1.0, 1.0, 0.0));
  // A collinear face has angles (0, 0, π): degenerate, not shapeless.
  EXPECT_FALSE(is_shapeless_triangle(1.0, 4.0, 9.0));
  EXPECT_FALSE(is_shapeless_triangle(1e-300, 1e-300, 1e-300));
}

}  // namespace
}  // namespace toonwater
