// Water-flow regions: ridge/valley by |K| > T and the sign of H, a scale-free threshold, the
// region of interest, and the free surface of closed liquid volumes.
#include "analyzer/flow_regions.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/analyzer/water_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace toonwater::test {
namespace {

struct Flow {
  Curvature curvature;
  FlowRegions regions;
};

Flow flow_of(const TriangleMesh& mesh, FlowOptions options = {}) {
  options.up = Axis::z;
  Flow f{curvature_of(mesh), {}};
  f.regions = find_flow_regions(f.curvature.mesh, f.curvature.topology.vertex_faces,
                                f.curvature.field, options);
  return f;
}

std::size_t nearest_vertex(const TriangleMesh& m, double x, double y) {
  std::size_t best = 0;
  for (std::size_t v = 1; v < m.positions.size(); ++v)
    if (std::hypot(m.positions[v].x() - x, m.positions[v].y() - y) <
        std::hypot(m.positions[best].x() - x, m.positions[best].y() - y))
      best = v;
  return best;
}

TEST(FlowRegions, FlatWaterHasNoLabels) {
  const Flow f = flow_of(height_field(41, [](double, double) { return 0.3; }));
  EXPECT_EQ(f.regions.ridge_vertices + f.regions.valley_vertices, 0u);
  EXPECT_TRUE(f.regions.region_of_interest.empty());
  EXPECT_DOUBLE_EQ(f.regions.rest_height, 0.3);
  EXPECT_NEAR(f.regions.median_edge_length, 0.05, 1e-12);
}

TEST(FlowRegions, BumpIsARidgeAndDipAValley) {
  const TriangleMesh m = height_field(81, [](double x, double y) {
    return bump(0.2, -0.5, 0.0, 0.15)(x, y) - bump(0.2, 0.5, 0.0, 0.15)(x, y);
  });
  const Flow f = flow_of(m);
  EXPECT_GT(f.regions.ridge_vertices, 10u);
  EXPECT_GT(f.regions.valley_vertices, 10u);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, -0.5, 0.0)], FlowLabel::ridge);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, 0.5, 0.0)], FlowLabel::valley);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    if (f.regions.label[v] == FlowLabel::none) continue;
    EXPECT_GT(std::abs(f.curvature.field.gaussian[v]), f.regions.threshold);
    EXPECT_EQ(f.regions.label[v] == FlowLabel::ridge, f.curvature.field.mean[v] > 0.0);
    EXPECT_LT(std::abs(std::abs(m.positions[v].x()) - 0.5), 0.5) << "label far from the bumps";
  }
}

TEST(FlowRegions, DefaultThresholdIsScaleFree) {
  const TriangleMesh m = height_field(61, bump(0.2, 0.0, 0.0, 0.2));
  const Flow reference = flow_of(m);
  ASSERT_GT(reference.regions.ridge_vertices, 0u);
  for (double scale : {1e-3, 1e3}) {
    TriangleMesh scaled = m;
    for (Vec3& p : scaled.positions) p *= scale;
    const Flow f = flow_of(scaled);
    EXPECT_NEAR(f.regions.threshold * scale * scale, reference.regions.threshold,
                1e-12 * reference.regions.threshold);
    EXPECT_EQ(f.regions.label, reference.regions.label) << "scale " << scale;
  }
}

TEST(FlowRegions, AbsoluteThresholdOverridesTheRelativeOne) {
  const TriangleMesh m = height_field(61, bump(0.2, 0.0, 0.0, 0.2));
  FlowOptions options;
  options.k_threshold = 1e9;
  const Flow f = flow_of(m, options);
  EXPECT_EQ(f.regions.threshold, 1e9);
  EXPECT_EQ(f.regions.ridge_vertices + f.regions.valley_vertices, 0u);
}

TEST(FlowRegions, RegionOfInterestExcludesUndisplacedWater) {
  // A displaced bump on the left and, far to the right, a ripple too small to count as
  // displacement but curved enough to pass a low threshold.
  const TriangleMesh m = height_field(101, [](double x, double y) {
    return bump(0.2, -0.6, 0.0, 0.12)(x, y) + bump(0.004, 0.7, 0.0, 0.05)(x, y);
  });
  FlowOptions options;
  options.k_threshold = 0.05;
  options.rest_height = 0.0;
  options.region_of_interest = false;
  const Flow everywhere = flow_of(m, options);
  EXPECT_NE(everywhere.regions.label[nearest_vertex(m, 0.7, 0.0)], FlowLabel::none);
  options.region_of_interest = true;
  const Flow roi = flow_of(m, options);
  EXPECT_EQ(roi.regions.label[nearest_vertex(m, 0.7, 0.0)], FlowLabel::none);
  EXPECT_EQ(roi.regions.label[nearest_vertex(m, -0.6, 0.0)], FlowLabel::ridge);
  EXPECT_LT(roi.regions.region_of_interest.max.x(), 0.0);
}

TEST(FlowRegions, TankWallsFloorAndCornersNeverBecomeFlowRegions) {
  const TriangleMesh m = tank(41, [](double x, double y) { return 0.1 * std::sin(4 * x) * std::cos(3 * y); });
  FlowOptions options;
  options.region_of_interest = false;  // even with the whole mesh in play
  options.k_threshold = 1e-6;          // and a threshold every corner passes
  const Flow f = flow_of(m, options);
  EXPECT_EQ(f.curvature.topology.boundary_vertices, 0u);  // the tank is closed
  EXPECT_EQ(f.curvature.flipped, 0u);
  std::size_t labelled = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3& p = m.positions[v];
    const bool on_wall_or_floor = p.z() == -1.0 || std::abs(p.x()) == 1.0 || std::abs(p.y()) == 1.0;
    if (on_wall_or_floor) {
      EXPECT_EQ(f.regions.label[v], FlowLabel::none) << v;
    }
    labelled += f.regions.label[v] != FlowLabel::none;
  }
  EXPECT_GT(labelled, 100u);  // the free surface itself is labelled
  // The top's interior, less one ring next to the walls.
  EXPECT_EQ(f.regions.free_surface_vertices, 37u * 37u);
}

TEST(FlowRegions, RestHeightOfATankIsItsFreeSurface) {
  const TriangleMesh m = tank(41, bump(0.1, 0.0, 0.0, 0.2));
  const Flow f = flow_of(m);
  EXPECT_NEAR(f.regions.rest_height, 0.0, 1e-3);  // not pulled down by the floor at −1
  EXPECT_FALSE(f.regions.region_of_interest.empty());
  EXPECT_LT(f.regions.region_of_interest.max.x(), 0.6);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, 0.0, 0.0)], FlowLabel::ridge);
}

}  // namespace
}  // namespace toonwater::test
