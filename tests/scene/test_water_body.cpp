// The surface cut along an iso-line (scene/level_split.hpp) and the edge it gives between a
// closed volume's free surface and its body (scene/water_body.hpp).
#include "scene/level_split.hpp"
#include "scene/mesh2_writer.hpp"
#include "scene/water_body.hpp"

#include "analyzer/geometry_tolerances.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "tests/analyzer/water_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>

namespace toonwater::test {
namespace {

double area(const SceneMesh& m, const Triangle& t) {
  return 0.5 * (m.positions[t[1]] - m.positions[t[0]])
                   .cross(m.positions[t[2]] - m.positions[t[0]])
                   .norm();
}

// Each directed edge once and its reverse once: closed and consistently wound.
void expect_closed(const SceneMesh& m) {
  std::map<std::pair<int, int>, int> directed;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1);
    EXPECT_EQ(directed.count({edge.second, edge.first}), 1U);
  }
}

SceneMesh unit_sphere_scene() {
  const TriangleMesh sphere = make_uv_sphere(24, 48, 1.0).mesh;
  std::vector<Vec3> normals;
  for (const Vec3& p : sphere.positions) normals.push_back(p.normalized());
  return make_scene_mesh(sphere, normals, true, Axis::y);
}

TEST(LevelSplit, CutsAClosedSurfaceAlongTheIsoLineAndKeepsItClosed) {
  PreparedSurface s;
  s.mesh = unit_sphere_scene();
  const double level = 0.3137;
  std::vector<double> field;
  std::vector<TextureCoordinate> uv;
  for (const Vec3& p : s.mesh.positions) {
    field.push_back(p.y());
    uv.push_back({static_cast<float>(p.y()), 0.5F});
  }
  s.flow_field = field;
  double area_before = 0;
  for (const Triangle& t : s.mesh.triangles) area_before += area(s.mesh, t);
  const std::size_t vertices_before = s.mesh.positions.size();

  const std::vector<bool> above = split_at_level(s, uv, field, level);

  ASSERT_EQ(above.size(), s.mesh.triangles.size());
  ASSERT_EQ(uv.size(), s.mesh.positions.size());
  ASSERT_EQ(s.flow_field.size(), s.mesh.positions.size());
  ASSERT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
  EXPECT_GT(s.mesh.positions.size(), vertices_before) << "the iso-line crosses faces";
  expect_closed(s.mesh);
  double area_after = 0;
  int faces_above = 0;
  for (std::size_t f = 0; f < s.mesh.triangles.size(); ++f) {
    const Triangle& t = s.mesh.triangles[f];
    area_after += area(s.mesh, t);
    faces_above += above[f];
    EXPECT_FALSE(is_degenerate_triangle(s.mesh.positions[t[0]], s.mesh.positions[t[1]],
                                        s.mesh.positions[t[2]]));
    // The field is linear in y: a face above has no corner below the level, nor one below a
    // corner above it.
    for (const int v : t) {
      if (above[f])
        EXPECT_GE(s.mesh.positions[v].y(), level - 1e-12);
      else
        EXPECT_LE(s.mesh.positions[v].y(), level + 1e-12);
    }
  }
  EXPECT_GT(faces_above, 0);
  EXPECT_LT(faces_above, static_cast<int>(above.size()));
  EXPECT_NEAR(area_after, area_before, 1e-12 * area_before);
  // The cut points lie on the iso-line, with every value interpolated there.
  for (std::size_t v = vertices_before; v < s.mesh.positions.size(); ++v) {
    EXPECT_NEAR(s.mesh.positions[v].y(), level, 1e-12);
    EXPECT_NEAR(s.flow_field[v], level, 1e-12);
    EXPECT_NEAR(uv[v][0], level, 1e-6);
    EXPECT_NEAR(s.mesh.normals[v].norm(), 1.0, 1e-12);
    EXPECT_GT(s.mesh.normals[v].dot(s.mesh.positions[v]), 0.99);
  }
}

TEST(LevelSplit, AnIsoLineThroughACornerIsNotCutBesideIt) {
  // A square of two faces; corner 3 lies on the level, corner 2 within the margin of it.
  PreparedSurface s;
  s.mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 1), Vec3(0, 0, 1)};
  s.mesh.normals.assign(4, Vec3(0, 1, 0));
  s.mesh.triangles = {{0, 2, 1}, {0, 3, 2}};
  std::vector<TextureCoordinate> uv;
  const std::vector<double> field{0.0, 1.0, 0.5 + 0.5 * level_split_margin, 0.5};
  const std::vector<bool> above = split_at_level(s, uv, field, 0.5);
  // Edge 0–1 is cut at its middle; edges 0–2 and 2–3 end on their corners 2 and 3.
  ASSERT_EQ(s.mesh.positions.size(), 5U);
  EXPECT_TRUE(s.mesh.positions[4].isApprox(Vec3(0.5, 0, 0)));
  double up = 0, down = 0;
  for (std::size_t f = 0; f < s.mesh.triangles.size(); ++f) {
    const Triangle& t = s.mesh.triangles[f];
    EXPECT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
    (above[f] ? up : down) += area(s.mesh, t);
  }
  EXPECT_NEAR(up + down, 1.0, 1e-12);
  EXPECT_NEAR(up, 0.25, 1e-12);  // the triangle (0.5, 0) – (1, 0) – (1, 1)
}

// A corner just off the level is the cut's end on one of its edges and not on the other: the
// iso-line runs along the face's edge from it, and the face is cut into pieces none of them flat.
TEST(LevelSplit, AnIsoLineAlongAFacesEdgeLeavesNoFlatPiece) {
  PreparedSurface s;
  s.mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 0, 1)};
  s.mesh.normals.assign(3, Vec3(0, 1, 0));
  s.mesh.triangles = {{0, 2, 1}};
  std::vector<TextureCoordinate> uv;
  const std::vector<double> field{0.5 - 0.001, 0.5 + 0.0011, 1.0};
  const std::vector<bool> above = split_at_level(s, uv, field, 0.5);
  ASSERT_EQ(s.mesh.positions.size(), 4U) << "one cut point, on the edge from 0 to 1";
  double total = 0;
  for (std::size_t f = 0; f < s.mesh.triangles.size(); ++f) {
    const Triangle& t = s.mesh.triangles[f];
    EXPECT_FALSE(is_degenerate_triangle(s.mesh.positions[t[0]], s.mesh.positions[t[1]],
                                        s.mesh.positions[t[2]]));
    EXPECT_TRUE(above[f]);
    total += area(s.mesh, t);
  }
  EXPECT_NEAR(total, 0.5, 1e-12);
}

// A tank with a flat top: the edge between its walls and its water is straight and sharp, and
// stays where it is; only at the tank's four corners, where one face of water meets two of
// wall, does the body take a sliver of the corner faces.
TEST(WaterBody, ASharpStraightEdgeBetweenWallsAndWaterStaysWhereItIs) {
  const int n = 21;
  const TriangleMesh tank_mesh = tank(n, [](double, double) { return 0.0; });
  std::vector<Vec3> normals(tank_mesh.positions.size(), Vec3::Zero());
  for (const Triangle& t : tank_mesh.triangles) {
    const Vec3 normal = (tank_mesh.positions[t[1]] - tank_mesh.positions[t[0]])
                            .cross(tank_mesh.positions[t[2]] - tank_mesh.positions[t[0]]);
    for (const int v : t) normals[v] += normal;
  }
  PreparedSurface s;
  s.mesh = make_scene_mesh(tank_mesh, normals, true, Axis::z);
  const std::vector<bool> before = upward_faces(s.mesh);
  std::vector<TextureCoordinate> uv;
  const std::vector<bool> surface = cut_free_surface_from_body(s, uv);
  const std::vector<bool> by_normal = upward_faces(s.mesh);
  expect_closed(s.mesh);
  double water = 0, taken = 0, given = 0;
  for (std::size_t f = 0; f < s.mesh.triangles.size(); ++f) {
    const double a = area(s.mesh, s.mesh.triangles[f]);
    if (surface[f]) water += a;
    taken += (by_normal[f] && !surface[f]) ? a : 0.0;
    given += (!by_normal[f] && surface[f]) ? a : 0.0;
  }
  const double cell = 2.0 / (n - 1);
  EXPECT_EQ(given, 0.0) << "no wall or floor is drawn as water";
  EXPECT_LE(taken, 4 * 0.5 * cell * cell) << "at most a corner face's worth at each corner";
  EXPECT_NEAR(water, 4.0, 2 * cell * cell);
  EXPECT_LE(s.mesh.triangles.size(), before.size() + 4 * 3);
}

// A box of water of twelve faces: its top's corners are the box's corners, where one face of
// water meets two of wall (φ = 1/3), so the iso-line would leave nothing of the top. The top
// stays water and the walls and floor stay body, none of them cut.
TEST(WaterBody, ACoarseBoxKeepsItsTopAsWater) {
  const TriangleMesh box = water_box();
  std::vector<Vec3> normals;
  for (const Vec3& p : box.positions) normals.push_back(p - Vec3(0, -0.2, 0));
  PreparedSurface s;
  s.mesh = make_scene_mesh(box, normals, true, Axis::y);
  const std::vector<bool> by_normal = upward_faces(s.mesh);
  std::vector<TextureCoordinate> uv;
  const std::vector<bool> surface = cut_free_surface_from_body(s, uv);
  ASSERT_EQ(s.mesh.triangles.size(), 12U);
  EXPECT_EQ(surface, by_normal);
  EXPECT_EQ(std::count(surface.begin(), surface.end(), true), 2);
}

}  // namespace
}  // namespace toonwater::test
