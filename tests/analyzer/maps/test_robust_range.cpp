// Robust colour ranges: the weighted quantile of |value|, merged over frames.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/maps/map_planner.hpp"
#include "analyzer/maps/robust_range.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace toonwater {
namespace {

// Reported quantiles are bin upper edges: at or above the exact value, at most 1/64 above.
constexpr double bin_ratio = 1.0 + 1.0 / 64.0;

TEST(RobustRange, QuantileOfUniformValuesIsWithinOneBin) {
  AbsQuantileHistogram h;
  for (int i = 1; i <= 1000; ++i) h.add((i % 2 ? 1 : -1) * i * 1e-3, 1.0);
  const double q = h.quantile(0.98);
  EXPECT_GE(q, 0.980);
  EXPECT_LE(q, 0.980 * bin_ratio);
}

TEST(RobustRange, OutliersBelowTheTwoPercentTailDoNotSetTheRange) {
  AbsQuantileHistogram h;
  h.add(2.0, 99.0);
  h.add(-1e6, 1.0);  // one spike with 1 % of the weight
  EXPECT_GE(h.quantile(0.98), 2.0);
  EXPECT_LE(h.quantile(0.98), 2.0 * bin_ratio);
}

TEST(RobustRange, EmptyZeroAndInvalidSamples) {
  AbsQuantileHistogram h;
  EXPECT_EQ(h.quantile(0.98), 0.0);
  h.add(0.0, 1.0);
  h.add(std::numeric_limits<double>::quiet_NaN(), 1.0);
  h.add(5.0, 0.0);
  h.add(5.0, std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(h.total_weight(), 1.0);
  EXPECT_EQ(h.quantile(0.98), 0.0);
  h.add(std::numeric_limits<double>::infinity(), 1.0);  // counted at float's largest value
  EXPECT_LE(h.quantile(1.0), std::numeric_limits<float>::max());
  EXPECT_GE(h.quantile(1.0), std::numeric_limits<float>::max() / bin_ratio);
}

TEST(RobustRange, MergingEqualsAddingEverythingToOne) {
  AbsQuantileHistogram a, b, all;
  for (int i = 0; i < 500; ++i) {
    a.add(std::sin(i) * 3.0, 1.0 + i % 3);
    all.add(std::sin(i) * 3.0, 1.0 + i % 3);
    b.add(std::cos(i) * 7.0, 0.5);
    all.add(std::cos(i) * 7.0, 0.5);
  }
  a.merge(b);
  for (double q : {0.5, 0.9, 0.98}) EXPECT_EQ(a.quantile(q), all.quantile(q));
}

// The planner's range of a sequence is the quantile over all frames pooled: between the
// quiet and the loud frame's own ranges, and the same whichever frame comes first.
TEST(RobustRange, PlannerPoolsFramesOfASequence) {
  const Analysis quiet = test::analyse(make_wave_field(81, 0.02).mesh, Axis::z);
  const Analysis loud = test::analyse(make_wave_field(81, 0.1).mesh, Axis::z);
  MapPlanner quiet_only(Axis::z), loud_only(Axis::z), both(Axis::z), reversed(Axis::z);
  quiet_only.add(quiet);
  loud_only.add(loud);
  both.add(quiet);
  both.add(loud);
  reversed.add(loud);
  reversed.add(quiet);
  const MapRanges q = quiet_only.ranges(), l = loud_only.ranges(), s = both.ranges();
  EXPECT_GT(l.gaussian, q.gaussian);
  EXPECT_GT(s.gaussian, q.gaussian);
  EXPECT_LE(s.gaussian, l.gaussian);
  EXPECT_GT(s.mean, q.mean);
  EXPECT_LE(s.mean, l.mean);
  EXPECT_EQ(s.gaussian, reversed.ranges().gaussian);
  EXPECT_EQ(s.mean, reversed.ranges().mean);
  EXPECT_EQ(both.frames(), 2u);
}

TEST(RobustRange, PlannerViewFollowsTheMedianEdgeOrTheGivenSize) {
  const Analysis wave = test::analyse(make_wave_field(101, 0.05, 6.0, 1.0).mesh, Axis::z);
  MapPlanner planner(Axis::z);
  planner.add(wave);
  const MapView derived = planner.view(MapOptions{});
  // 100 grid steps over 2 units, two pixels per median edge (a grid step or a diagonal).
  EXPECT_GE(derived.width, 100);
  EXPECT_LE(derived.width, 200);
  EXPECT_EQ(derived.width, derived.height);
  MapOptions sized;
  sized.size = 300;
  EXPECT_EQ(planner.view(sized).width, 300);
  EXPECT_NEAR(planner.view(sized).pixel_size, 2.0 / 300, 1e-12);
  MapPlanner empty(Axis::z);
  EXPECT_THROW(empty.view(MapOptions{}), std::runtime_error);
}

}  // namespace
}  // namespace toonwater
