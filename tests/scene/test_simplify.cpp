// The render mesh's simplification (scene/simplify.hpp): what it removes, what it keeps, and
// the rendered picture against the full mesh.
#include "scene/simplify.hpp"

#include "pipeline/generate_scene.hpp"
#include "scene/frame_include.hpp"

#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

double ripple(double x, double z) {
  const double r2 = x * x + z * z;
  return 0.04 * std::exp(-r2 / 0.08) * std::cos(25.0 * std::sqrt(r2));
}

// Squared distance from p to the triangle abc: the plane's when p projects inside it, else the
// nearest edge's (the test's own, independent of the simplifier's).
double point_triangle_squared(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double area2 = n.squaredNorm();
  // Barycentric coordinates of p's projection; inside: the plane distance.
  const Vec3 q = p - n.dot(p - a) / area2 * n;
  const double u = (c - b).cross(q - b).dot(n) / area2, v = (a - c).cross(q - c).dot(n) / area2;
  if (u >= 0 && v >= 0 && u + v <= 1) return (p - q).squaredNorm();
  auto segment = [&](const Vec3& s, const Vec3& t) {
    const double h = std::clamp((p - s).dot(t - s) / (t - s).squaredNorm(), 0.0, 1.0);
    return (p - (s + h * (t - s))).squaredNorm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// One-sided Hausdorff distance from the points to the mesh's surface.
double distance_to_surface(const std::vector<Vec3>& points, const SceneMesh& mesh) {
  double worst = 0;
  for (const Vec3& p : points) {
    double best = std::numeric_limits<double>::infinity();
    for (const Triangle& t : mesh.triangles)
      best = std::min(best, point_triangle_squared(p, mesh.positions[t[0]], mesh.positions[t[1]],
                                                   mesh.positions[t[2]]));
    worst = std::max(worst, std::sqrt(best));
  }
  return worst;
}

// Points of the mesh's faces: corners, edge midpoints and centroids.
std::vector<Vec3> surface_samples(const SceneMesh& mesh) {
  std::vector<Vec3> s;
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    s.insert(s.end(), {a, 0.5 * (a + b), 0.5 * (b + c), 0.5 * (c + a), (a + b + c) / 3.0});
  }
  return s;
}

PreparedSurface prepared(TriangleMesh mesh) {
  return prepare_surface(std::move(mesh), Axis::y, nullptr, nullptr);
}

SimplifyStats simplify(PreparedSurface& s, double tolerance) {
  SceneConfig config;
  std::vector<TextureCoordinate> uv = texture_coordinates(s, light_geometry(config.light, Axis::y));
  return simplify_surface(
      s, uv,
      simplify_options(config.water, {config.water.t_bright, config.water.t_medium}, nullptr,
                       tolerance));
}

TEST(Simplify, FlatPlaneSimplifiesToAHandfulOfFacesWithItsOutline) {
  PreparedSurface s = prepared(make_height_grid(41, 1.0, [](double, double) { return 0.0; }));
  const SimplifyStats stats = simplify(s, 1e-3);
  EXPECT_TRUE(stats.simplified);
  EXPECT_EQ(stats.faces_before, 3200u);
  EXPECT_LE(stats.faces_after, 8u);
  EXPECT_EQ(s.mesh.triangles.size(), stats.faces_after);
  EXPECT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
  // The square keeps its corners: the outline does not move.
  Vec3 lo = s.mesh.positions[0], hi = lo;
  for (const Vec3& p : s.mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  EXPECT_NEAR(lo.x(), -1.0, 1e-12);
  EXPECT_NEAR(hi.x(), 1.0, 1e-12);
  EXPECT_NEAR(lo.z(), -1.0, 1e-12);
  EXPECT_NEAR(hi.z(), 1.0, 1e-12);
  double area = 0;
  for (const Triangle& t : s.mesh.triangles)
    area += 0.5 * (s.mesh.positions[t[1]] - s.mesh.positions[t[0]])
                      .cross(s.mesh.positions[t[2]] - s.mesh.positions[t[0]])
                      .norm();
  EXPECT_NEAR(area, 4.0, 1e-9);
}

TEST(Simplify, AVertexInNoFaceIsLeftOut) {
  TriangleMesh plane = make_height_grid(11, 1.0, [](double, double) { return 0.0; });
  plane.positions.push_back(Vec3(5, 0, 5));
  PreparedSurface s = prepared(plane);
  ASSERT_EQ(s.mesh.positions.size(), 122u);
  const SimplifyStats stats = simplify(s, 1e-3);
  EXPECT_TRUE(stats.simplified);
  EXPECT_LE(stats.faces_after, 8u);
  for (const Vec3& p : s.mesh.positions) EXPECT_LE(p.norm(), std::sqrt(2.0) + 1e-12);
}

// The geometric tolerance is the pixel bound at the test camera; the simplified surface stays
// within it of every original point (and the other way round), and the crests are kept.
TEST(Simplify, RippleKeepsItsCrestsWithinThePixelBound) {
  const TriangleMesh input = make_height_grid(61, 1.0, ripple);
  PreparedSurface s = prepared(input);
  const SceneMesh full = s.mesh;
  SceneConfig config;
  config.camera.location = Vec3(0, 2.5, -2.5);
  config.water.simplify = 0.5;
  config.render.width = 320;
  config.render.height = 180;
  SceneLayout layout;
  layout.config = &config;
  layout.camera = frame_camera(config, Axis::y, full.min, full.max);
  const CameraReach reach = camera_reach(layout, full.min, full.max);
  const double tolerance =
      screen_tolerance(0.5, reach.nearest_distance, config.camera.angle, 320, 180);
  ASSERT_GT(tolerance, 0.0);
  ASSERT_LT(tolerance, 0.01);
  std::vector<TextureCoordinate> uv = texture_coordinates(s, light_geometry(config.light, Axis::y));
  const SimplifyStats stats = simplify_water(s, uv, layout, nullptr);
  ASSERT_TRUE(stats.simplified);
  EXPECT_LT(stats.faces_after, stats.faces_before / 2);
  EXPECT_GT(stats.faces_after, 200u);  // the ripple needs its triangles
  EXPECT_LE(distance_to_surface(full.positions, s.mesh), tolerance);
  EXPECT_LE(distance_to_surface(surface_samples(s.mesh), full), tolerance);
  double top_full = -1, top = -1;
  for (const Vec3& p : full.positions) top_full = std::max(top_full, p.y());
  for (const Vec3& p : s.mesh.positions) top = std::max(top, p.y());
  EXPECT_DOUBLE_EQ(top, top_full);
}

TEST(Simplify, EmptyDegenerateAndNonManifoldFramesPassThroughUnchanged) {
  PreparedSurface empty;
  EXPECT_FALSE(simplify(empty, 0.1).simplified);
  EXPECT_TRUE(empty.mesh.triangles.empty());

  TriangleMesh flat_faces;  // every face has zero area
  flat_faces.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  flat_faces.triangles = {{0, 1, 2}, {1, 2, 3}};
  PreparedSurface degenerate = prepared(flat_faces);
  EXPECT_FALSE(simplify(degenerate, 0.1).simplified);
  EXPECT_EQ(degenerate.mesh.positions.size(), 4u);

  // A flat grid with a fin: three faces on one edge.
  TriangleMesh fin = make_height_grid(9, 1.0, [](double, double) { return 0.0; });
  const int a = fin.triangles[40][0], b = fin.triangles[40][1];
  fin.positions.push_back(0.5 * (fin.positions[a] + fin.positions[b]) + Vec3(0, 0.5, 0));
  fin.triangles.push_back({a, b, static_cast<int>(fin.positions.size() - 1)});
  PreparedSurface nonmanifold = prepared(fin);
  const std::vector<Triangle> before = nonmanifold.mesh.triangles;
  EXPECT_FALSE(simplify(nonmanifold, 0.1).simplified);
  EXPECT_EQ(nonmanifold.mesh.triangles, before);
}

TEST(Simplify, ScreenToleranceIsThePixelBoundAtTheNearestPoint) {
  // 1 pixel at 10 units with a 90° field on a square 100-pixel image: f = 50 pixels, so the
  // centre's pixel spans 0.2; the corners' rays are sqrt(3) times longer at the same depth.
  EXPECT_NEAR(screen_tolerance(1.0, 10.0, 90.0, 100, 100), 0.2 / 3.0, 1e-12);
  EXPECT_EQ(screen_tolerance(0.0, 10.0, 90.0, 100, 100), 0.0);
  EXPECT_EQ(screen_tolerance(1.0, 0.0, 90.0, 100, 100), 0.0);
}

// The picture of a simplified frame against the full one, with the default scene (refraction,
// reflection, outlines, flow regions) and a ripple on calm water.
TEST(Simplify, RenderedFrameMatchesTheFullMesh) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(101, 1.0, ripple));
  auto render = [&](const std::string& name, const std::string& simplify) {
    const fs::path out = dir / name;
    const CommandResult r =
        run_toonwater({"povgen", "--out", out.string(), "--water", (dir / "water.obj").string(),
                       "--set", "water.simplify=" + simplify, "--set", "render.width=160", "--set",
                       "render.height=90", "--set", "render.antialias=false"});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    const Povray p = run_povray(out);
    EXPECT_EQ(p.exit_code, 0) << p.output;
    return read_image(out / "frame.png");
  };
  const Image full = render("full", "0"), simplified = render("simplified", "0.5");
  ASSERT_EQ(full.pixels.size(), simplified.pixels.size());
  ASSERT_GT(full.pixels.size(), 0u);
  std::size_t differing = 0;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x) differing += !near(full.at(x, y), simplified.at(x, y), 16);
  EXPECT_LE(static_cast<double>(differing), 0.005 * full.width * full.height);
  EXPECT_LT(fs::file_size(dir / "simplified" / "water_0000.inc"),
            fs::file_size(dir / "full" / "water_0000.inc") / 2);
}

}  // namespace
}  // namespace toonwater::test
