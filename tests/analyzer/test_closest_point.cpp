// The closest point of a triangle: against a brute-force search over a fine grid of the
// triangle's points, from points in every Voronoi region (inside, beyond each edge and each
// corner, above and below the plane); weights non-negative and summing to one.
#include "analyzer/closest_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace toonwater::test {
namespace {

// The least squared distance from p to the points a·u + b·v + c·(1 − u − v) on a grid of the
// triangle with `steps` steps a side.
double brute_force_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                             int steps) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= steps; ++i)
    for (int j = 0; i + j <= steps; ++j) {
      const double u = double(i) / steps, v = double(j) / steps;
      best = std::min(best, (p - (u * a + v * b + (1 - u - v) * c)).squaredNorm());
    }
  return best;
}

TEST(ClosestPoint, AgreesWithABruteForceSearchFromEveryRegion) {
  const Vec3 a(0.1, -0.2, 0.0), b(1.3, 0.1, 0.2), c(0.4, 0.9, -0.1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1.0, 2.0);
  for (int trial = 0; trial < 400; ++trial) {
    const Vec3 p(coordinate(rng), coordinate(rng), 0.5 * coordinate(rng));
    const TrianglePoint q = closest_point_on_triangle(p, a, b, c);
    const Vec3 point = q.weights[0] * a + q.weights[1] * b + q.weights[2] * c;
    EXPECT_NEAR(q.weights.sum(), 1.0, 1e-12);
    EXPECT_GE(q.weights.minCoeff(), -1e-12) << p.transpose();
    EXPECT_NEAR((p - point).squaredNorm(), q.distance2, 1e-12);
    // The grid's points lie on the triangle: none is nearer; its nearest is within the grid's
    // spacing (1/400 of the longest edge) of the answer.
    const double grid = brute_force_distance2(p, a, b, c, 400);
    EXPECT_LE(q.distance2, grid + 1e-12) << p.transpose();
    EXPECT_NEAR(std::sqrt(q.distance2), std::sqrt(grid), 0.01) << p.transpose();
  }
}

TEST(ClosestPoint, APointOverTheInsideProjectsOntoThePlane) {
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const TrianglePoint q = closest_point_on_triangle(Vec3(0.2, 0.3, 0.5), a, b, c);
  EXPECT_NEAR(q.distance2, 0.25, 1e-15);
  EXPECT_NEAR(q.weights[0], 0.5, 1e-15);
  EXPECT_NEAR(q.weights[1], 0.2, 1e-15);
  EXPECT_NEAR(q.weights[2], 0.3, 1e-15);
}

// Two corners at one place: the answer is a corner or the edge to the third, never weights that
// are not numbers with a distance that is one (a caller picks faces by the distance).
TEST(ClosestPoint, ACollapsedTriangleGivesNoNonFiniteWeightsWithAFiniteDistance) {
  const Vec3 a(0, 0, 0), c(1, 0, 0);
  for (const Vec3& p : {Vec3(0.5, 0.5, 0), Vec3(-1, 0.2, 0), Vec3(2, -0.1, 0.3), Vec3(0, 1, 0)}) {
    const TrianglePoint q = closest_point_on_triangle(p, a, a, c);
    if (std::isfinite(q.distance2)) {
      EXPECT_TRUE(q.weights.allFinite()) << p.transpose();
    }
  }
}

}  // namespace
}  // namespace toonwater::test
