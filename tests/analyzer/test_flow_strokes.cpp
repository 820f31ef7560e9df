// Flow strokes (analyzer/flow_strokes.hpp): one tapered stroke along a narrow region's crest,
// the contour around a wide one.
#include "analyzer/flow_strokes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace toonwater::test {
namespace {

// A flat n × n grid of unit cells in z = 0, with a flow field s(x, y) on every vertex.
struct Grid {
  TriangleMesh mesh;
  VertexFaces vertex_faces;
  FlowRegions flow;
};
Grid grid(int n, const std::function<double(double, double)>& s) {
  Grid g;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      g.mesh.positions.emplace_back(i, j, 0.0);
      const double v = s(i, j);
      g.flow.field.push_back(v);
      g.flow.label.push_back(v >= 1    ? FlowLabel::ridge
                             : v <= -1 ? FlowLabel::valley
                                       : FlowLabel::none);
      g.flow.free_surface.push_back(1);
      g.flow.shading_normal.emplace_back(0, 0, 1);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      g.mesh.triangles.push_back({a, b, d});
      g.mesh.triangles.push_back({a, d, c});
    }
  g.vertex_faces = build_vertex_faces(g.mesh.positions.size(), g.mesh.triangles);
  return g;
}

// A ridge three cells wide and thirty long, and a valley disc of radius 4.
TEST(FlowStrokes, ANarrowCrestIsOneTaperedStrokeAlongItsMiddleAndAWideRegionKeepsItsContour) {
  const Grid g = grid(41, [](double x, double y) {
    if (x >= 5 && x <= 35 && std::abs(y - 20) <= 1) return 2.0 - std::abs(y - 20);
    if (std::hypot(x - 20, y - 7) <= 4) return -2.0;
    return 0.0;
  });
  const std::vector<FlowLine> lines = flow_strokes(g.mesh, g.vertex_faces, g.flow, 3.0);
  ASSERT_EQ(lines.size(), 2u);
  int strokes = 0, contours = 0;
  for (const FlowLine& line : lines) {
    if (line.sign == FlowLabel::ridge) {
      ++strokes;
      EXPECT_FALSE(line.closed);
      double lo = 1e9, hi = -1e9;
      for (const Vec3& p : line.points) {
        EXPECT_NEAR(p.y(), 20.0, 0.25) << "off the crest at x = " << p.x();
        EXPECT_NEAR(p.z(), 0.0, 1e-12) << "smoothing leaves the surface's plane";
        lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
      }
      EXPECT_LE(lo, 6.0);
      EXPECT_GE(hi, 34.0);
      EXPECT_EQ(line.taper.front(), 0.0);
      EXPECT_EQ(line.taper.back(), 0.0);
      EXPECT_EQ(line.taper[line.taper.size() / 2], 1.0);
    } else {
      ++contours;
      EXPECT_TRUE(line.closed);
      for (const Vec3& p : line.points) EXPECT_NEAR(std::hypot(p.x() - 20, p.y() - 7), 4.0, 1.0);
    }
  }
  EXPECT_EQ(strokes, 1);
  EXPECT_EQ(contours, 1);
}

// The field is strongest along y = 21 in a region from y = 19 to 21: the stroke keeps to it.
TEST(FlowStrokes, TheStrokeFollowsWhereTheFieldIsStrongest) {
  const Grid g = grid(41, [](double x, double y) {
    if (x >= 5 && x <= 35 && y >= 19 && y <= 21) return y == 21 ? 4.0 : 1.2;
    return 0.0;
  });
  const std::vector<FlowLine> lines = flow_strokes(g.mesh, g.vertex_faces, g.flow, 3.0);
  ASSERT_EQ(lines.size(), 1u);
  int on_crest = 0;
  for (const Vec3& p : lines[0].points) on_crest += std::abs(p.y() - 21.0) < 0.5;
  EXPECT_GE(on_crest, 0.8 * static_cast<double>(lines[0].points.size()));
}

// A crest whose peak lies between two rows of vertices, at y = 20.3: the stroke lies on it,
// not on the row of vertices nearest to it.
TEST(FlowStrokes, TheStrokeLiesWhereTheCrestPeaksBetweenTheVertices) {
  const Grid g = grid(41, [](double x, double y) {
    const double v = 3.0 - (y - 20.3) * (y - 20.3);
    return x >= 5 && x <= 35 && v >= 1.0 ? v : 0.0;
  });
  const std::vector<FlowLine> lines = flow_strokes(g.mesh, g.vertex_faces, g.flow, 3.0);
  ASSERT_EQ(lines.size(), 1u);
  for (const Vec3& p : lines[0].points) EXPECT_NEAR(p.y(), 20.3, 0.05) << "at x = " << p.x();
}

// A crest one vertex wide along the border of an open surface: its edges belong to one face
// each, and still join it into one stroke.
TEST(FlowStrokes, ACrestAlongTheSurfacesBorderIsOneStroke) {
  const Grid g =
      grid(41, [](double x, double y) { return y == 40 && x >= 5 && x <= 35 ? 2.0 : 0.0; });
  const std::vector<FlowLine> lines = flow_strokes(g.mesh, g.vertex_faces, g.flow, 3.0);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_FALSE(lines[0].closed);
  double lo = 1e9, hi = -1e9;
  for (const Vec3& p : lines[0].points) {
    EXPECT_NEAR(p.y(), 40.0, 1e-9) << "a contour around the crest, not a stroke along it";
    lo = std::min(lo, p.x()), hi = std::max(hi, p.x());
  }
  EXPECT_LE(lo, 6.0);
  EXPECT_GE(hi, 34.0);
}

// Regions smaller than A_min are specks fading in or out: neither a short crest nor a small
// disc among them gets a stroke, while the larger crest and disc keep theirs.
TEST(FlowStrokes, SpecksBelowTheSmallestRegionDrawnHaveNoStroke) {
  const Grid g = grid(41, [](double x, double y) {
    if (x >= 5 && x <= 35 && std::abs(y - 20) <= 1) return 2.0 - std::abs(y - 20);  // area 60
    if (std::hypot(x - 20, y - 7) <= 4) return -2.0;                                // about 50
    if (x >= 5 && x <= 8 && std::abs(y - 32) <= 1) return 2.0;                      // 6
    if (std::hypot(x - 32, y - 32) <= 1.5) return -2.0;                             // about 4
    return 0.0;
  });
  Grid with_limit = g;
  with_limit.flow.min_region_area = 20.0;
  EXPECT_EQ(flow_strokes(g.mesh, g.vertex_faces, g.flow, 3.0).size(), 4u)
      << "without a limit, every region";
  const std::vector<FlowLine> lines =
      flow_strokes(with_limit.mesh, with_limit.vertex_faces, with_limit.flow, 3.0);
  ASSERT_EQ(lines.size(), 2u);
  for (const FlowLine& line : lines)
    for (const Vec3& p : line.points) EXPECT_LT(p.y(), 25.0) << "a stroke on a speck";
}

}  // namespace
}  // namespace toonwater::test
