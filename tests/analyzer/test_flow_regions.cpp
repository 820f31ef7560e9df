// Water-flow regions: the flow field on H (default) and the paper's |K| rule, thresholds that
// are scale- and resolution-free, ripple rings, specks, and the free surface of closed volumes.
#include "analyzer/flow_regions.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/analyzer/flow_test_util.hpp"
#include "tests/analyzer/water_meshes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

namespace toonwater::test {
namespace {

std::size_t nearest_vertex(const TriangleMesh& m, double x, double y) {
  std::size_t best = 0;
  for (std::size_t v = 1; v < m.positions.size(); ++v)
    if (std::hypot(m.positions[v].x() - x, m.positions[v].y() - y) <
        std::hypot(m.positions[best].x() - x, m.positions[best].y() - y))
      best = v;
  return best;
}

TEST(FlowRegions, FlatWaterHasNoLabels) {
  const Flow f = flow_of(height_field(21, [](double, double) { return 0.3; }));
  EXPECT_EQ(f.regions.ridge_vertices + f.regions.valley_vertices, 0u);
  EXPECT_TRUE(f.regions.region_of_interest.empty());
  EXPECT_DOUBLE_EQ(f.regions.rest_height, 0.3);
  EXPECT_NEAR(f.regions.scale_length, 2.0, 1e-2);  // sqrt of the 2 × 2 sheet's area
  for (double s : f.regions.field) EXPECT_EQ(s, 0.0);
}

TEST(FlowRegions, BumpIsARidgeAndDipAValley) {
  const TriangleMesh m = height_field(61, [](double x, double y) {
    return bump(0.1, -0.5, 0.0, 0.2)(x, y) - bump(0.1, 0.5, 0.0, 0.2)(x, y);
  });
  const Flow f = flow_of(m);
  EXPECT_GT(f.regions.ridge_vertices, 10u);
  EXPECT_GT(f.regions.valley_vertices, 10u);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, -0.5, 0.0)], FlowLabel::ridge);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, 0.5, 0.0)], FlowLabel::valley);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const double s = f.regions.field[v];
    ASSERT_TRUE(std::isfinite(s));
    EXPECT_EQ(f.regions.label[v], s >= 1.0    ? FlowLabel::ridge
                                  : s <= -1.0 ? FlowLabel::valley
                                              : FlowLabel::none);
    if (f.regions.label[v] == FlowLabel::none) continue;
    EXPECT_TRUE(f.regions.region_of_interest.contains(m.positions[v]));
    EXPECT_LT(std::abs(std::abs(m.positions[v].x()) - 0.5), 0.5) << "label far from the bumps";
  }
}

// The paper's rule is kept as it was, bar the threshold: ridge where |K| > T and H > 0, valley
// where |K| > T and H < 0, no smoothing, no speck fading (away from the free surface's border).
TEST(FlowRegions, PaperCriterionIsThePapersRule) {
  const TriangleMesh m = height_field(61, [](double x, double y) {
    return 0.05 * std::sin(5 * x) * std::cos(4 * y) + bump(0.1, 0.3, 0.2, 0.15)(x, y);
  });
  FlowOptions options;
  options.criterion = FlowCriterion::paper;
  options.threshold = 4.0;
  const Flow f = flow_of(m, options);
  ASSERT_GT(f.regions.ridge_vertices, 20u);
  ASSERT_GT(f.regions.valley_vertices, 20u);
  const auto& c = f.curvature.field;
  const auto& vf = f.curvature.topology.vertex_faces;
  std::size_t checked = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    bool interior = f.regions.free_surface[v];
    for (std::int32_t face : vf.of(static_cast<std::int32_t>(v)))
      for (std::int32_t w : m.triangles[face]) interior = interior && f.regions.free_surface[w];
    if (!interior) continue;
    const std::int8_t rule = std::abs(c.gaussian[v]) > 4.0 && c.mean[v] > 0   ? FlowLabel::ridge
                             : std::abs(c.gaussian[v]) > 4.0 && c.mean[v] < 0 ? FlowLabel::valley
                                                                              : FlowLabel::none;
    EXPECT_EQ(f.regions.label[v], rule) << v;
    ++checked;
  }
  EXPECT_GT(checked, 3000u);
}

TEST(FlowRegions, DefaultThresholdIsScaleFree) {
  const TriangleMesh m = height_field(41, bump(0.1, 0.0, 0.0, 0.25));
  for (const FlowCriterion criterion : {FlowCriterion::mean, FlowCriterion::paper}) {
    FlowOptions options;
    options.criterion = criterion;
    const Flow reference = flow_of(m, options);
    ASSERT_GT(reference.regions.ridge_vertices, 0u);
    const double power = criterion == FlowCriterion::mean ? 1.0 : 2.0;  // T in 1/length^power
    for (const double scale : {1e-3, 1e3}) {
      TriangleMesh scaled = m;
      for (Vec3& p : scaled.positions) p *= scale;
      const Flow f = flow_of(scaled, options);
      EXPECT_NEAR(f.regions.threshold * std::pow(scale, power), reference.regions.threshold,
                  1e-9 * reference.regions.threshold);
      EXPECT_EQ(f.regions.label, reference.regions.label) << "scale " << scale;
    }
  }
}

TEST(FlowRegions, AbsoluteThresholdOverridesTheRelativeOne) {
  const TriangleMesh m = height_field(41, bump(0.1, 0.0, 0.0, 0.25));
  FlowOptions options;
  options.threshold = 1e9;
  const Flow f = flow_of(m, options);
  EXPECT_EQ(f.regions.threshold, 1e9);
  EXPECT_EQ(f.regions.ridge_vertices + f.regions.valley_vertices, 0u);
}

// A region smaller than A_min is not drawn, and regions fade in as they grow: the drawn area
// never jumps.
TEST(FlowRegions, SpecksFadeOutAndGrowingRegionsFadeIn) {
  FlowOptions options;
  options.min_region_area = 0.02;
  options.threshold = 2.0;
  double last_area = 0.0;
  bool seen_hidden = false, seen_drawn = false;
  for (double width = 0.04; width <= 0.25; width += 0.0075) {
    const TriangleMesh m = height_field(121, bump(0.5 * width, 0.0, 0.0, width));
    const Flow f = flow_of(m, options);
    double drawn = 0.0, above_one_before_fading = 0.0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      if (f.regions.label[v] == FlowLabel::ridge) drawn += f.curvature.field.area[v];
      if (f.regions.smoothed_field[v] >= 1.0) above_one_before_fading += f.curvature.field.area[v];
    }
    if (above_one_before_fading > 0 && above_one_before_fading < options.min_region_area.value()) {
      EXPECT_EQ(drawn, 0.0) << width;
      seen_hidden = true;
    }
    if (above_one_before_fading >= 2 * options.min_region_area.value()) {
      EXPECT_DOUBLE_EQ(drawn, above_one_before_fading) << width;
      seen_drawn = true;
    }
    if (above_one_before_fading < 2 * options.min_region_area.value()) {
      EXPECT_GE(drawn, last_area - 1e-12) << width;  // fading in as it grows
    }
    EXPECT_LE(drawn - last_area, 0.5 * options.min_region_area.value())
        << "jump at width " << width;
    last_area = drawn;
  }
  EXPECT_TRUE(seen_hidden);
  EXPECT_TRUE(seen_drawn);
}

// The region of interest only reports where the regions are: a small ripple far from the
// displaced water is labelled all the same.
TEST(FlowRegions, RegionOfInterestNeverRemovesARegion) {
  const TriangleMesh m = height_field(101, [](double x, double y) {
    return bump(0.2, -0.6, 0.0, 0.12)(x, y) + bump(0.004, 0.7, 0.0, 0.05)(x, y);
  });
  FlowOptions options;
  options.threshold = 0.5;
  options.rest_height = 0.0;
  options.min_region_area = 0.0;
  const Flow f = flow_of(m, options);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, 0.7, 0.0)], FlowLabel::ridge);
  EXPECT_EQ(f.regions.label[nearest_vertex(m, -0.6, 0.0)], FlowLabel::ridge);
  EXPECT_GT(f.regions.region_of_interest.max.x(), 0.7);
}

TEST(FlowRegions, TankWallsFloorAndCornersNeverBecomeFlowRegions) {
  const TriangleMesh m =
      tank(41, [](double x, double y) { return 0.1 * std::sin(4 * x) * std::cos(3 * y); });
  FlowOptions options;
  options.threshold = 1e-6;  // a threshold every corner passes
  options.min_region_area = 0.0;
  const Flow f = flow_of(m, options);
  EXPECT_EQ(f.curvature.topology.boundary_vertices, 0u);  // the tank is closed
  EXPECT_EQ(f.curvature.flipped, 0u);
  std::size_t labelled = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const Vec3& p = m.positions[v];
    const bool on_wall_or_floor = p.z() == -1.0 || std::abs(p.x()) == 1.0 || std::abs(p.y()) == 1.0;
    if (on_wall_or_floor) {
      EXPECT_EQ(f.regions.label[v], FlowLabel::none) << v;
      EXPECT_EQ(f.regions.field[v], 0.0) << v;
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

// `analyze` leaves the shading normals out; what it writes must not change with them.
TEST(FlowRegions, LeavingTheShadingNormalsOutChangesNothingElse) {
  const TriangleMesh m = tank(41, [](double x, double y) {
    return 0.05 * std::sin(5 * x) * std::cos(4 * y) + bump(0.1, 0.3, 0.2, 0.15)(x, y);
  });
  const Flow with = flow_of(m);
  FlowOptions options;
  options.shading_normals = false;
  const Flow without = flow_of(m, options);
  EXPECT_EQ(with.regions.shading_normal.size(), m.positions.size());
  EXPECT_GT(with.regions.normal_noise, 0.0);
  EXPECT_TRUE(without.regions.shading_normal.empty());
  EXPECT_EQ(without.regions.normal_noise, 0.0);
  EXPECT_GT(with.regions.ridge_vertices + with.regions.valley_vertices, 0u);
  EXPECT_EQ(without.regions.field, with.regions.field);
  EXPECT_EQ(without.regions.smoothed_field, with.regions.smoothed_field);
  EXPECT_EQ(without.regions.label, with.regions.label);
  EXPECT_EQ(without.regions.threshold, with.regions.threshold);
  EXPECT_EQ(without.regions.regions, with.regions.regions);
}

}  // namespace
}  // namespace toonwater::test
