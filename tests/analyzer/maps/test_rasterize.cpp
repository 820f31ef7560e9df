// Top-down rasteriser: analytic values at known pixels, barycentric interpolation, the topmost
// layer, culling of downward faces, axes.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/maps/map_planner.hpp"
#include "analyzer/maps/top_down_map.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace toonwater {
namespace {

using test::analyse;
using test::centred_options;

std::size_t index(const MapView& view, int x, int y) {
  return static_cast<std::size_t>(y) * view.width + x;
}

TopDownMap map_of(const Analysis& a, Axis up, const MapOptions& options) {
  MapPlanner planner(up);
  planner.add(a);
  return rasterize_top_down(a.surface, a.curvature, a.flow.label, a.flow.free_surface,
                            planner.view(options));
}

// Curvature given directly, so a test controls every vertex value.
CurvatureField constant_curvature(std::size_t vertices, double k, double h) {
  CurvatureField c;
  c.gaussian.assign(vertices, k);
  c.mean.assign(vertices, h);
  return c;
}

// A horizontal square [−s, s]² at height z, facing up (+z) or down.
void add_square(TriangleMesh& mesh, double s, double z, bool up = true) {
  const auto base = static_cast<std::int32_t>(mesh.positions.size());
  mesh.positions.insert(mesh.positions.end(),
                        {Vec3(-s, -s, z), Vec3(s, -s, z), Vec3(s, s, z), Vec3(-s, s, z)});
  if (up) {
    mesh.triangles.push_back({base, base + 1, base + 2});
    mesh.triangles.push_back({base, base + 2, base + 3});
  } else {
    mesh.triangles.push_back({base, base + 2, base + 1});
    mesh.triangles.push_back({base, base + 3, base + 2});
  }
}

// Closed sphere, radius 2 (K = 1/4, H = 1/2): the map shows only the upper hemisphere, and
// the centre pixel matches the analytic values within 2 % (the cotangent operators' error on
// this icosphere plus interpolation across one triangle).
TEST(MapRasterize, SphereCapCentreMatchesAnalyticCurvature) {
  const AnalyticSurface sphere = make_icosphere(5, 2.0);
  const TopDownMap map = map_of(analyse(sphere.mesh, Axis::z), Axis::z, centred_options(2.0, 101));
  ASSERT_EQ(map.view.width, 101);
  ASSERT_EQ(map.view.height, 101);
  const std::size_t centre = index(map.view, 50, 50);
  EXPECT_EQ(map.alpha[centre], 1.0f);
  EXPECT_NEAR(map.gaussian[centre], 0.25, 0.02 * 0.25);
  EXPECT_NEAR(map.mean[centre], 0.5, 0.02 * 0.5);
  EXPECT_NEAR(map.k1[centre], 0.5, 0.02 * 0.5);
  EXPECT_NEAR(map.k2[centre], 0.5, 0.02 * 0.5);
  EXPECT_NEAR(map.height[centre], 2.0, 1e-3);  // the top, not the bottom of the sphere

  // Alpha marks the disk: a corner of the box lies outside, and holds 0 in every channel.
  const std::size_t corner = index(map.view, 0, 0);
  EXPECT_EQ(map.alpha[corner], 0.0f);
  for (const auto* channel : {&map.height, &map.gaussian, &map.mean, &map.k1, &map.k2, &map.label})
    EXPECT_EQ((*channel)[corner], 0.0f);
  // Only the free surface of the closed sphere is drawn: its upward cap (slopes below 60°,
  // free_surface.hpp), never the lower hemisphere.
  const double covered = static_cast<double>(map.covered_pixels) / (101.0 * 101.0);
  EXPECT_GT(covered, 0.4);
  EXPECT_LT(covered, std::numbers::pi / 4.0);
  for (std::size_t i = 0; i < map.alpha.size(); ++i) {
    if (map.alpha[i] > 0.0f) {
      ASSERT_GT(map.height[i], 0.5);
    }
  }
}

// Saddle z = (x² − y²)/2: at the centre K = −1, H = 0 (tolerance 0.02).
TEST(MapRasterize, SaddleCentreMatchesAnalyticCurvature) {
  const AnalyticSurface saddle = make_saddle(81, 0.5);
  const TopDownMap map = map_of(analyse(saddle.mesh, Axis::z), Axis::z, centred_options(0.5, 81));
  const std::size_t centre = index(map.view, 40, 40);
  EXPECT_EQ(map.alpha[centre], 1.0f);
  EXPECT_NEAR(map.gaussian[centre], -1.0, 0.02);
  EXPECT_NEAR(map.mean[centre], 0.0, 0.02);
  EXPECT_NEAR(map.k1[centre], 1.0, 0.02);
  EXPECT_NEAR(map.k2[centre], -1.0, 0.02);
}

TEST(MapRasterize, PlaneMapsToZeroEverywhereItCovers) {
  const AnalyticSurface plane = make_wave_field(41, 0.0);
  const TopDownMap map = map_of(analyse(plane.mesh, Axis::z), Axis::z, MapOptions{});
  ASSERT_GT(map.covered_pixels, 0u);
  EXPECT_EQ(map.covered_pixels, map.alpha.size());  // the extent is the plane's own
  for (std::size_t i = 0; i < map.alpha.size(); ++i) {
    ASSERT_EQ(map.alpha[i], 1.0f);
    ASSERT_NEAR(map.gaussian[i], 0.0, 1e-9);
    ASSERT_NEAR(map.mean[i], 0.0, 1e-9);
    ASSERT_EQ(map.label[i], 0.0f);
    ASSERT_NEAR(map.height[i], 0.0, 1e-12);
  }
}

// A linear function is reproduced exactly at every pixel centre by barycentric interpolation;
// a nearest-vertex map of this two-triangle plane would be off by up to half its slope · size.
TEST(MapRasterize, InterpolatesBarycentricallyNotNearestVertex) {
  TriangleMesh mesh;
  add_square(mesh, 1.0, 0.0);
  for (Vec3& p : mesh.positions) p.z() = 0.3 * p.x() - 0.2 * p.y();
  CurvatureField c = constant_curvature(4, 0.0, 0.0);
  for (std::size_t v = 0; v < 4; ++v) c.gaussian[v] = 5.0 * mesh.positions[v].x();
  MapView view{Axis::z, {-1, -1, 1, 1}, 64, 64, 2.0 / 64};
  const TopDownMap map = rasterize_top_down(mesh, c, {}, {}, view);
  EXPECT_EQ(map.covered_pixels, 64u * 64u);
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const double u = -1 + (x + 0.5) * view.pixel_size, v = 1 - (y + 0.5) * view.pixel_size;
      ASSERT_NEAR(map.height[index(view, x, y)], 0.3 * u - 0.2 * v, 1e-6);
      ASSERT_NEAR(map.gaussian[index(view, x, y)], 5.0 * u, 1e-5);
    }
}

TEST(MapRasterize, TopmostLayerWinsWhateverTheFaceOrder) {
  for (bool top_first : {false, true}) {
    TriangleMesh mesh;
    add_square(mesh, top_first ? 0.5 : 1.0, top_first ? 1.0 : 0.0);
    add_square(mesh, top_first ? 1.0 : 0.5, top_first ? 0.0 : 1.0);
    CurvatureField c = constant_curvature(8, 0.0, 0.0);
    for (std::size_t v = 0; v < 8; ++v) c.gaussian[v] = mesh.positions[v].z() > 0.5 ? -3.0 : 5.0;
    const MapView view{Axis::z, {-1, -1, 1, 1}, 20, 20, 0.1};
    const TopDownMap map = rasterize_top_down(mesh, c, {}, {}, view);
    EXPECT_FLOAT_EQ(map.height[index(view, 10, 10)], 1.0f);  // inside the upper square
    EXPECT_FLOAT_EQ(map.gaussian[index(view, 10, 10)], -3.0f);
    EXPECT_FLOAT_EQ(map.height[index(view, 1, 1)], 0.0f);  // only the lower one there
    EXPECT_FLOAT_EQ(map.gaussian[index(view, 1, 1)], 5.0f);
  }
}

TEST(MapRasterize, DownwardFacesAreNotDrawn) {
  TriangleMesh mesh;
  add_square(mesh, 1.0, 1.0, /*up=*/false);  // e.g. the underside of an overhang or a floor
  const MapView view{Axis::z, {-1, -1, 1, 1}, 10, 10, 0.2};
  const TopDownMap map = rasterize_top_down(mesh, constant_curvature(4, 1, 1), {}, {}, view);
  EXPECT_EQ(map.covered_pixels, 0u);
}

// Given a free-surface selection, faces with a corner off it are not drawn.
TEST(MapRasterize, OnlyFacesOnTheFreeSurfaceAreDrawn) {
  TriangleMesh mesh;
  add_square(mesh, 1.0, 0.0);
  const std::vector<std::uint8_t> selected{1, 1, 1, 0};  // the face (0, 2, 3) is off
  const MapView view{Axis::z, {-1, -1, 1, 1}, 40, 40, 0.05};
  const TopDownMap all = rasterize_top_down(mesh, constant_curvature(4, 0, 0), {}, {}, view);
  const TopDownMap some = rasterize_top_down(mesh, constant_curvature(4, 0, 0), {}, selected, view);
  EXPECT_EQ(all.covered_pixels, 40u * 40u);
  EXPECT_EQ(some.alpha[index(view, 37, 37)], 1.0f);  // face (0, 1, 2), below the diagonal
  EXPECT_EQ(some.alpha[index(view, 2, 2)], 0.0f);    // face (0, 2, 3)
  EXPECT_NEAR(static_cast<double>(some.covered_pixels), 40.0 * 41.0 / 2.0, 1.0);
}

// Labels are categorical: each pixel takes its nearest corner's label, never a blend.
TEST(MapRasterize, LabelIsTheNearestCornersLabel) {
  TriangleMesh mesh;
  add_square(mesh, 1.0, 0.0);
  const std::vector<std::int8_t> label{FlowLabel::valley, FlowLabel::ridge, FlowLabel::ridge,
                                       FlowLabel::none};
  const MapView view{Axis::z, {-1, -1, 1, 1}, 40, 40, 0.05};
  const TopDownMap map = rasterize_top_down(mesh, constant_curvature(4, 0, 0), label, {}, view);
  EXPECT_EQ(map.label[index(view, 2, 37)], -1.0f);  // next to (−1, −1)
  EXPECT_EQ(map.label[index(view, 37, 37)], 1.0f);  // next to (1, −1)
  EXPECT_EQ(map.label[index(view, 2, 2)], 0.0f);    // next to (−1, 1)
  for (float l : map.label) ASSERT_TRUE(l == -1.0f || l == 0.0f || l == 1.0f);
}

// The same wave field exported Z-up and Y-up (x, y, z) → (x, z, −y) gives the same map.
TEST(MapRasterize, YUpAndZUpGiveTheSameTopView) {
  const AnalyticSurface wave = make_wave_field(61, 0.1, 5.0);
  TriangleMesh y_up = wave.mesh;
  for (Vec3& p : y_up.positions) p = Vec3(p.x(), p.z(), -p.y());
  const TopDownMap z_map = map_of(analyse(wave.mesh, Axis::z), Axis::z, MapOptions{});
  const TopDownMap y_map = map_of(analyse(y_up, Axis::y), Axis::y, MapOptions{});
  ASSERT_EQ(z_map.view.width, y_map.view.width);
  ASSERT_EQ(z_map.view.height, y_map.view.height);
  for (std::size_t i = 0; i < z_map.alpha.size(); ++i) {
    ASSERT_EQ(z_map.alpha[i], y_map.alpha[i]);
    ASSERT_NEAR(z_map.gaussian[i], y_map.gaussian[i], 1e-4 * (1 + std::abs(z_map.gaussian[i])));
    ASSERT_NEAR(z_map.height[i], y_map.height[i], 1e-6);
  }
}

TEST(MapRasterize, ValuesBeyondFloatRangeAreClampedNotInfinite) {
  TriangleMesh mesh;
  add_square(mesh, 1.0, 0.0);
  const MapView view{Axis::z, {-1, -1, 1, 1}, 8, 8, 0.25};
  const TopDownMap map =
      rasterize_top_down(mesh, constant_curvature(4, 1e300, -1e300), {}, {}, view);
  constexpr float largest = std::numeric_limits<float>::max();
  std::size_t covered = 0;
  for (std::size_t i = 0; i < map.alpha.size(); ++i) {
    ASSERT_TRUE(std::isfinite(map.gaussian[i]));
    ASSERT_TRUE(std::isfinite(map.mean[i]));
    if (map.alpha[i] == 0) continue;
    ++covered;
    EXPECT_EQ(map.gaussian[i], largest);  // clamped to float's range, sign kept
    EXPECT_EQ(map.mean[i], -largest);
  }
  EXPECT_GT(covered, map.alpha.size() / 4);
}

}  // namespace
}  // namespace toonwater
