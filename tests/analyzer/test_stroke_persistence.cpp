// Strokes that persist from frame to frame (analyzer/stroke_persistence.hpp): held still where
// the traced crest only jitters, followed where it travels, faded in and out where they were.
#include "analyzer/stroke_persistence.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace toonwater::test {
namespace {

// A flat 41 × 21 grid of unit cells in z = 0 (shifted by `dx`), all free surface, normals up.
struct Water {
  TriangleMesh mesh;
  FlowRegions flow;
};
Water flat_water(double dx = 0.0) {
  Water w;
  const int nx = 41, ny = 21;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      w.mesh.positions.emplace_back(i + dx, j, 0.0);
      w.flow.free_surface.push_back(1);
      w.flow.shading_normal.emplace_back(0, 0, 1);
    }
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      w.mesh.triangles.push_back({a, b, d});
      w.mesh.triangles.push_back({a, d, c});
    }
  w.flow.median_edge_length = 1.0;
  return w;
}

constexpr double kTaper = 3.0;

// A ridge stroke along x from x0 to x1 at height y, a point every edge.
FlowLine crest(double y, double x0 = 5, double x1 = 35) {
  FlowLine line;
  line.sign = FlowLabel::ridge;
  for (double x = x0; x <= x1 + 1e-9; x += 1.0) line.points.emplace_back(x, y, 0.0);
  set_taper(line, kTaper);
  return line;
}

double widest(const FlowLine& line) {
  return *std::max_element(line.taper.begin(), line.taper.end());
}

double mean_y(const FlowLine& line) {
  double sum = 0;
  for (const Vec3& p : line.points) sum += p.y();
  return sum / static_cast<double>(line.points.size());
}

TEST(StrokePersistence, ACrestTracedAnEdgeAwayByNoiseIsHeldWhereItWasDrawn) {
  const Water w = flat_water();
  StrokePersistence persistence;
  double before = 0;
  for (int frame = 0; frame < 12; ++frame) {
    const double traced = 10.0 + (frame % 2 ? 0.8 : -0.8);  // jumps 1.6 edges every frame
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {crest(traced)}, kTaper);
    ASSERT_EQ(drawn.size(), 1u) << "frame " << frame;
    const double y = mean_y(drawn[0]);
    if (frame >= 4) {
      EXPECT_LT(std::abs(y - before), 0.4)
          << "frame " << frame << ": the stroke jumps with the noise";
    }
    before = y;
  }
}

TEST(StrokePersistence, ATravellingCrestIsFollowedAsOneStroke) {
  const Water w = flat_water();
  for (const double speed : {1.5, 2.5}) {  // edges a frame: below and beyond the noise distance
    StrokePersistence persistence;
    for (int frame = 0; frame < 7; ++frame) {
      const double traced = 3.0 + speed * frame;
      const std::vector<FlowLine> drawn =
          persistence.update(w.mesh, w.flow, {crest(traced)}, kTaper);
      ASSERT_EQ(drawn.size(), 1u) << "speed " << speed << ", frame " << frame
                                  << ": the stroke breaks or leaves a trail";
      EXPECT_LE(traced - mean_y(drawn[0]), 1.0)
          << "lags an edge behind: speed " << speed << ", frame " << frame;
      EXPECT_GE(traced - mean_y(drawn[0]), -1e-12);
      if (speed > StrokePersistenceOptions{}.noise_distance) {
        EXPECT_NEAR(mean_y(drawn[0]), traced, 1e-12)
            << "a move beyond the noise is taken as traced";
      }
    }
  }
}

TEST(StrokePersistence, AStrokeFadesInAndThinsOutWhereItWas) {
  const Water w = flat_water();
  StrokePersistence persistence;
  const int fade = StrokePersistenceOptions{}.fade_frames;
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {}, kTaper).empty()) << "a first frame, calm";
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {crest(10)}, kTaper).empty())
      << "a stroke traced in one frame only is never drawn";
  for (int frame = 1; frame <= fade + 1; ++frame) {
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
    ASSERT_EQ(drawn.size(), 1u);
    EXPECT_NEAR(widest(drawn[0]), std::min(1.0, frame / static_cast<double>(fade)), 1e-12)
        << "frame " << frame;
  }
  for (int gone = 1; gone < fade; ++gone) {
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {}, kTaper);
    ASSERT_EQ(drawn.size(), 1u) << gone << " frames after its crest went";
    EXPECT_NEAR(widest(drawn[0]), 1.0 - static_cast<double>(gone) / fade, 1e-12);
    EXPECT_NEAR(mean_y(drawn[0]), 10.0, 1e-12);
    EXPECT_EQ(drawn[0].points.size(), crest(10).points.size());
  }
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {}, kTaper).empty());
}

TEST(StrokePersistence, AStrokeTracedInOneFrameOnlyIsNeverDrawn) {
  const Water w = flat_water();
  StrokePersistence persistence;
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {}, kTaper).empty());
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {crest(10)}, kTaper).empty());
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {}, kTaper).empty());
}

// A fading stroke is hidden only where another is drawn over it (cover_distance), not where
// one merely passes near: a crest that ends an edge from it leaves it whole.
TEST(StrokePersistence, AFadingStrokeIsCoveredOnlyWhereAnotherIsDrawnOverIt) {
  const Water w = flat_water();
  StrokePersistence persistence;
  persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
  FlowLine across;  // from an edge beside the fading crest, away from it along y
  across.sign = FlowLabel::ridge;
  for (double y = 11; y <= 19 + 1e-9; y += 1.0) across.points.emplace_back(20.0, y, 0.0);
  set_taper(across, kTaper);
  for (int frame = 1; frame <= 2; ++frame) {
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {across}, kTaper);
    const auto fading = std::count_if(drawn.begin(), drawn.end(),
                                      [](const FlowLine& l) { return mean_y(l) < 10.5; });
    EXPECT_EQ(fading, 1) << "frame " << frame << ": the crest is cut where the other ends";
    for (const FlowLine& l : drawn) {
      if (mean_y(l) < 10.5) {
        EXPECT_EQ(l.points.size(), crest(10).points.size());
      }
    }
  }
}

TEST(StrokePersistence, ThePartOfAStrokeItsSuccessorNoLongerCoversFadesOnItsOwn) {
  const Water w = flat_water();
  StrokePersistence persistence;
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
  const std::vector<FlowLine> drawn =
      persistence.update(w.mesh, w.flow, {crest(10, 5, 20)}, kTaper);
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_NEAR(widest(drawn[0]), 1.0, 1e-12);
  const FlowLine& rest = drawn[1];
  EXPECT_NEAR(widest(rest), 1.0 - 1.0 / StrokePersistenceOptions{}.fade_frames, 1e-12);
  // From the first point more than cover_distance past the successor's end (the points lie an
  // edge apart) to the stroke's own end: not snapped back to where the successor ends.
  const double cover = StrokePersistenceOptions{}.cover_distance;
  EXPECT_GT(rest.points.front().x(), 20.0 + cover);
  EXPECT_LE(rest.points.front().x(), 20.0 + cover + 1.0);
  EXPECT_NEAR(rest.points.back().x(), 35.0, 1e-12);
  EXPECT_EQ(rest.taper.front(), 0.0) << "the cut end tapers";
}

TEST(StrokePersistence, ASuccessorMovedSidewaysAndShorterLeavesOnlyThePartPastItsEndToFade) {
  const Water w = flat_water();
  StrokePersistence persistence;
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
  const StrokePersistenceOptions options;
  const double moved = 0.5 * (options.noise_distance + options.match_distance);  // followed
  const std::vector<FlowLine> drawn =
      persistence.update(w.mesh, w.flow, {crest(10 + moved, 5, 20)}, kTaper);
  ASSERT_EQ(drawn.size(), 2u) << "the successor and one fading piece, no trail beside it";
  EXPECT_NEAR(mean_y(drawn[0]), 10 + moved, 1e-12);
  const FlowLine& rest = drawn[1];
  EXPECT_NEAR(mean_y(rest), 10.0, 1e-12) << "fades where it was";
  // From the first point (an edge apart) more than cover_distance past the successor's end.
  EXPECT_GT(rest.points.front().x(), 20.0 + options.cover_distance);
  EXPECT_LE(rest.points.front().x(), 20.0 + options.cover_distance + 1.0);
  EXPECT_NEAR(rest.points.back().x(), 35.0, 1e-12);
}

TEST(StrokePersistence, ABendPastTheSuccessorsEndFadesOnItsOwn) {
  const Water w = flat_water();
  FlowLine hook = crest(10, 5, 20);  // along x, then bending away along y at x = 20
  for (double y = 11; y <= 18 + 1e-9; y += 1.0) hook.points.emplace_back(20.0, y, 0.0);
  set_taper(hook, kTaper);
  StrokePersistence persistence;
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, {hook}, kTaper);
  const std::vector<FlowLine> drawn =
      persistence.update(w.mesh, w.flow, {crest(10, 5, 20)}, kTaper);
  ASSERT_EQ(drawn.size(), 2u) << "the successor and the bend, which it does not follow";
  const FlowLine& bend = drawn[1];
  EXPECT_NEAR(widest(bend), 1.0 - 1.0 / StrokePersistenceOptions{}.fade_frames, 1e-12);
  // From the first point more than cover_distance from the successor's end to the hook's end.
  const double cover = StrokePersistenceOptions{}.cover_distance;
  EXPECT_GT(bend.points.front().y(), 10.0 + cover);
  EXPECT_LE(bend.points.front().y(), 10.0 + cover + 1.0);
  EXPECT_NEAR(bend.points.back().y(), 18.0, 1e-12);
}

TEST(StrokePersistence, AStrokeWhoseWaterHasGoneIsNotKept) {
  StrokePersistence persistence;
  const Water here = flat_water(), elsewhere = flat_water(100.0);
  for (int frame = 0; frame < 3; ++frame)
    persistence.update(here.mesh, here.flow, {crest(10)}, kTaper);
  EXPECT_TRUE(persistence.update(elsewhere.mesh, elsewhere.flow, {}, kTaper).empty());
}

TEST(StrokePersistence, StrokesOfTheOtherSignAreNeitherMatchedNorCovering) {
  const Water w = flat_water();
  StrokePersistence persistence;
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
  FlowLine trough = crest(10);
  trough.sign = FlowLabel::valley;
  const double step = 1.0 / StrokePersistenceOptions{}.fade_frames;
  const std::vector<FlowLine> first = persistence.update(w.mesh, w.flow, {trough}, kTaper);
  ASSERT_EQ(first.size(), 1u) << "the trough waits a frame to be drawn";
  EXPECT_EQ(first[0].sign, FlowLabel::ridge);
  EXPECT_NEAR(widest(first[0]), 1.0 - step, 1e-12) << "the crest fades: the trough is no match";
  const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {trough}, kTaper);
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_EQ(drawn[0].sign, FlowLabel::valley);
  EXPECT_NEAR(widest(drawn[0]), step, 1e-12);
  EXPECT_EQ(drawn[1].sign, FlowLabel::ridge);
  EXPECT_NEAR(widest(drawn[1]), 1.0 - 2 * step, 1e-12) << "nor does the trough cover it";
}

// The water's field s, the same at every vertex: how high the crest under a stroke stands.
void set_field(Water& w, double s) { w.flow.field.assign(w.mesh.positions.size(), s); }

TEST(StrokePersistence, AStrokeLivesWhileItsCrestStandsAtHalfTheRegionThreshold) {
  Water w = flat_water();
  const StrokePersistenceOptions options;
  const double step = 1.0 / options.fade_frames;
  StrokePersistence persistence;
  set_field(w, 1.2);
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, {crest(10)}, kTaper);
  set_field(w, options.hold_field + 0.1);  // under the region, so nothing is traced
  for (int frame = 0; frame < 8; ++frame) {
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {}, kTaper);
    ASSERT_EQ(drawn.size(), 1u) << "frame " << frame;
    EXPECT_NEAR(widest(drawn[0]), 1.0, 1e-12) << "frame " << frame << ": held, not faded";
    EXPECT_NEAR(mean_y(drawn[0]), 10.0, 1e-12);
  }
  set_field(w, options.hold_field - 0.1);  // the crest has gone: the stroke fades
  for (int gone = 1; gone < options.fade_frames; ++gone) {
    const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {}, kTaper);
    ASSERT_EQ(drawn.size(), 1u);
    EXPECT_NEAR(widest(drawn[0]), 1.0 - gone * step, 1e-12);
  }
  EXPECT_TRUE(persistence.update(w.mesh, w.flow, {}, kTaper).empty());
}

// Two edges apart: beside each other (within match_distance), not over each other (beyond
// cover_distance).
TEST(StrokePersistence, AStrokeIsNotHeldBesideADrawnStrokeOfItsCrest) {
  Water w = flat_water();
  const double step = 1.0 / StrokePersistenceOptions{}.fade_frames;
  StrokePersistence persistence;
  set_field(w, 1.2);
  for (int frame = 0; frame < 3; ++frame)
    persistence.update(w.mesh, w.flow, {crest(12), crest(10)}, kTaper);
  set_field(w, 0.9);
  const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {crest(12)}, kTaper);
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_NEAR(mean_y(drawn[0]), 12.0, 1e-12);
  EXPECT_NEAR(widest(drawn[0]), 1.0, 1e-12) << "the one traced";
  EXPECT_NEAR(mean_y(drawn[1]), 10.0, 1e-12);
  EXPECT_NEAR(widest(drawn[1]), 1.0 - step, 1e-12) << "the one beside it fades";
}

TEST(StrokePersistence, StrokesAreHeldOnlyAsFarAsTheSalienceLimitLeavesRoom) {
  Water w = flat_water();
  w.flow.max_regions = 2;
  const double step = 1.0 / StrokePersistenceOptions{}.fade_frames;
  StrokePersistence persistence;
  set_field(w, 1.2);
  const std::vector<FlowLine> crests{crest(3), crest(10, 5, 15), crest(17)};  // 31, 11, 31 points
  for (int frame = 0; frame < 3; ++frame) persistence.update(w.mesh, w.flow, crests, kTaper);
  set_field(w, 0.9);
  const std::vector<FlowLine> drawn = persistence.update(w.mesh, w.flow, {crest(17)}, kTaper);
  ASSERT_EQ(drawn.size(), 3u);
  EXPECT_NEAR(mean_y(drawn[0]), 17.0, 1e-12);
  EXPECT_NEAR(widest(drawn[0]), 1.0, 1e-12) << "traced";
  for (const FlowLine& line : {drawn[1], drawn[2]}) {
    EXPECT_NEAR(widest(line), mean_y(line) < 5 ? 1.0 : 1.0 - step, 1e-12)
        << "at y = " << mean_y(line) << ": room for one more, the longer";
  }
}

}  // namespace
}  // namespace toonwater::test
