// Small toon islands (scene/toon_islands.hpp): what is merged, into what, and what stays.
#include "scene/toon_islands.hpp"

#include "scene/scene_mesh.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace toonwater::test {
namespace {

// The faces of an n × n grid of vertices, vertex (i, j) at index i·n + j.
std::vector<Triangle> grid_triangles(int n) {
  std::vector<Triangle> t;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      t.push_back({a, b, d});
      t.push_back({a, d, c});
    }
  return t;
}

// Labels of an n × n grid: 0, with `block` set over rows and columns [lo, hi).
void fill(std::vector<int>& label, int n, int lo, int hi, int value) {
  for (int i = lo; i < hi; ++i)
    for (int j = lo; j < hi; ++j) label[i * n + j] = value;
}

TEST(ToonIslands, AnIslandBelowTheAreaIsMergedAndALargerOneStays) {
  constexpr int n = 20;
  std::vector<int> label(n * n, 0);
  label[2 * n + 2] = 1;      // one vertex
  fill(label, n, 8, 14, 1);  // 36 vertices
  const std::vector<double> area(n * n, 1.0), pixels(n * n, 100.0);
  EXPECT_EQ(merge_small_islands(grid_triangles(n), area, pixels, std::vector<double>{10.0, 10.0},
                                0.0, label),
            1u);
  EXPECT_EQ(label[2 * n + 2], 0);
  EXPECT_EQ(label[10 * n + 10], 1);
  int ones = 0;
  for (int l : label) ones += l == 1;
  EXPECT_EQ(ones, 36);
}

TEST(ToonIslands, AnIslandTooSmallOnScreenIsMergedWhateverItsArea) {
  constexpr int n = 20;
  std::vector<int> label(n * n, 0);
  fill(label, n, 8, 11, 1);  // 9 vertices
  std::vector<double> area(n * n, 1.0), pixels(n * n, 1.0);
  std::vector<int> near = label;
  EXPECT_EQ(merge_small_islands(grid_triangles(n), area, pixels, std::vector<double>{5.0, 5.0},
                                12.0, near),
            1u);
  EXPECT_EQ(near[9 * n + 9], 0) << "9 px < 12 px";
  for (double& p : pixels) p = 2.0;
  EXPECT_EQ(merge_small_islands(grid_triangles(n), area, pixels, std::vector<double>{5.0, 5.0},
                                12.0, label),
            0u);
  EXPECT_EQ(label[9 * n + 9], 1) << "18 px";
}

// A speck inside a ring of another class: merged first, it makes the ring larger, which is then
// judged at its new size.
TEST(ToonIslands, AnIslandGrownByAMergeIsJudgedAtItsNewSize) {
  constexpr int n = 20;
  std::vector<int> label(n * n, 0);
  fill(label, n, 8, 11, 1);
  label[9 * n + 9] = 2;  // the ring of 1 holds 8 vertices, with its centre 9
  const std::vector<double> area(n * n, 1.0), pixels(n * n, 100.0);
  std::vector<int> kept = label;
  EXPECT_EQ(merge_small_islands(grid_triangles(n), area, pixels, std::vector<double>{9.0, 9.0, 9.0},
                                0.0, kept),
            1u);
  EXPECT_EQ(kept[9 * n + 9], 1) << "the centre takes the ring's class, and the ring of 9 stays";
  EXPECT_EQ(kept[8 * n + 8], 1);
  EXPECT_EQ(merge_small_islands(grid_triangles(n), area, pixels,
                                std::vector<double>{10.0, 10.0, 10.0}, 0.0, label),
            2u);
  for (int l : label) EXPECT_EQ(l, 0) << "ring and centre are both too small for 10";
}

TEST(ToonIslands, AWholePartOfTheMeshInOneClassStays) {
  std::vector<Triangle> triangles = grid_triangles(3);
  triangles.push_back({9, 10, 11});  // a tiny separate triangle
  std::vector<int> label(12, 0);
  label[9] = label[10] = label[11] = 1;
  const std::vector<double> area(12, 1.0), pixels(12, 1.0);
  EXPECT_EQ(
      merge_small_islands(triangles, area, pixels, std::vector<double>{100.0, 100.0}, 100.0, label),
      0u);
  EXPECT_EQ(label[10], 1);
}

// On a flat 21 × 21 grid of unit cells seen from 10 above, a band speck takes the medium band's
// coordinates (moved just inside its limits), and a large bright patch keeps its coordinates
// bit for bit. A ridge speck of the same area stays while it shows (flow regions fade by their
// own least size): at a tenth of the pixel's size it is merged too.
TEST(ToonIslands, MergedVerticesMoveJustInsideTheirNewClass) {
  constexpr int n = 21;
  SceneMesh mesh;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      mesh.positions.emplace_back(i, 0.0, j);
      mesh.normals.emplace_back(0.0, 1.0, 0.0);
    }
  mesh.triangles = grid_triangles(n);
  mesh.min = Vec3(0, 0, 0);
  mesh.max = Vec3(n - 1, 0, n - 1);
  const ToonLimits limits{{0.4, 0.6}, std::make_pair(0.38, 0.62)};
  std::vector<TextureCoordinate> uv(n * n, TextureCoordinate{0.5f, 0.5f});
  uv[3 * n + 3][0] = 0.7f;   // bright speck
  uv[3 * n + 15][1] = 0.8f;  // ridge speck
  for (int i = 10; i < 18; ++i)
    for (int j = 10; j < 18; ++j) uv[i * n + j][0] = 0.65f + 0.001f * static_cast<float>(i + j);
  const std::vector<TextureCoordinate> before = uv;
  const Vec3 eye(10, 10, 10);
  const std::vector<double> pixel_width(n * n, 0.1);  // 100 px² a cell
  EXPECT_EQ(merge_toon_islands(mesh, eye, pixel_width, limits, IslandLimits{}, uv), 1u);
  EXPECT_LE(uv[3 * n + 3][0], 0.6f);
  EXPECT_GT(uv[3 * n + 3][0], 0.599f);
  EXPECT_EQ(uv[3 * n + 3][1], 0.5f);
  EXPECT_EQ(uv[3 * n + 15], before[3 * n + 15]);
  for (int i = 10; i < 18; ++i)
    for (int j = 10; j < 18; ++j) EXPECT_EQ(uv[i * n + j], before[i * n + j]);

  const std::vector<double> far_pixel_width(n * n, 1.0);  // 1 px² a cell
  EXPECT_EQ(merge_toon_islands(mesh, eye, far_pixel_width, limits, IslandLimits{}, uv), 1u);
  EXPECT_LT(uv[3 * n + 15][1], 0.62f);
  EXPECT_GT(uv[3 * n + 15][1], 0.619f);
  EXPECT_EQ(uv[3 * n + 15][0], 0.5f);
}

// A ridge region whose vertices lie in the bright band, in calm water of the medium band: the
// region's border vertices take the medium band, so no bright sliver lines the region; inside
// it, where nothing is interpolated out to the water, u stays.
TEST(ToonIslands, ARegionsBorderTakesTheBandAroundIt) {
  constexpr int n = 21;
  SceneMesh mesh;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      mesh.positions.emplace_back(i, 0.0, j);
      mesh.normals.emplace_back(0.0, 1.0, 0.0);
    }
  mesh.triangles = grid_triangles(n);
  const ToonLimits limits{{0.4, 0.6}, std::make_pair(0.38, 0.62)};
  std::vector<TextureCoordinate> uv(n * n, TextureCoordinate{0.5f, 0.5f});
  for (int i = 6; i < 15; ++i)
    for (int j = 6; j < 15; ++j) uv[i * n + j] = TextureCoordinate{0.7f, 0.8f};
  const std::vector<double> pixel_width(n * n, 0.1);
  merge_toon_islands(mesh, Vec3(10, 10, 10), pixel_width, limits, IslandLimits{}, uv);
  for (int i = 6; i < 15; ++i)
    for (int j = 6; j < 15; ++j) {
      const bool border = i == 6 || i == 14 || j == 6 || j == 14;
      EXPECT_EQ(uv[i * n + j][1], 0.8f) << "still the ridge";
      if (border) {
        EXPECT_LE(uv[i * n + j][0], 0.6f) << i << "," << j;
        EXPECT_GT(uv[i * n + j][0], 0.599f) << i << "," << j;
      } else {
        EXPECT_EQ(uv[i * n + j][0], 0.7f) << i << "," << j;
      }
    }
}

}  // namespace
}  // namespace toonwater::test
