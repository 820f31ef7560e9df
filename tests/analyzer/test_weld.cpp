// Welding: soups become connected meshes, the mapping covers every input vertex, first
// occurrences keep their order, +0 and -0 weld, distinct positions never do.
#include "analyzer/weld.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace toonwater {
namespace {

// The octahedron as an indexed mesh, and as a soup: each face with its own three corners.
TriangleMesh octahedron() {
  TriangleMesh mesh;
  mesh.positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                    Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  mesh.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                    {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return mesh;
}

TriangleMesh soup_of(const TriangleMesh& mesh) {
  TriangleMesh soup;
  for (const Triangle& t : mesh.triangles) {
    const auto first = static_cast<std::int32_t>(soup.positions.size());
    for (const std::int32_t corner : t) soup.positions.push_back(mesh.positions[corner]);
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  return soup;
}

TEST(Weld, OctahedronSoupWeldsToSixVertices) {
  const TriangleMesh indexed = octahedron();
  const TriangleMesh soup = soup_of(indexed);
  ASSERT_EQ(soup.positions.size(), 24u);

  const WeldedMesh welded = weld_coincident_vertices(soup);
  EXPECT_EQ(welded.mesh.positions.size(), 6u);
  EXPECT_EQ(welded.merged_vertex_count, 18u);
  ASSERT_EQ(welded.input_to_mesh.size(), 24u);
  for (std::size_t v = 0; v < soup.positions.size(); ++v)
    EXPECT_EQ(welded.mesh.positions[welded.input_to_mesh[v]], soup.positions[v]) << v;

  // Welded vertices in order of first occurrence in the soup: 0, 2, 4 (face 0), then 1 (face 1),
  // 3 (face 2), 5 (face 4) of the indexed octahedron.
  const std::vector<std::int32_t> indexed_of_welded{0, 2, 4, 1, 3, 5};
  for (std::size_t w = 0; w < 6; ++w)
    EXPECT_EQ(welded.mesh.positions[w], indexed.positions[indexed_of_welded[w]]) << w;
  ASSERT_EQ(welded.mesh.triangles.size(), 8u);
  for (std::size_t f = 0; f < 8; ++f)
    for (int c = 0; c < 3; ++c)
      EXPECT_EQ(indexed_of_welded[welded.mesh.triangles[f][c]], indexed.triangles[f][c]);
}

TEST(Weld, IndexedMeshIsUnchanged) {
  const TriangleMesh mesh = octahedron();
  const WeldedMesh welded = weld_coincident_vertices(mesh);
  EXPECT_EQ(welded.merged_vertex_count, 0u);
  EXPECT_EQ(welded.mesh.positions, mesh.positions);
  EXPECT_EQ(welded.mesh.triangles, mesh.triangles);
  EXPECT_EQ(welded.input_to_mesh, std::vector<std::int32_t>({0, 1, 2, 3, 4, 5}));
}

TEST(Weld, SignedZerosWeldAndTinyDifferencesDoNot) {
  TriangleMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(-0.0, 0, -0.0), Vec3(5e-324, 0, 0), Vec3(1, 2, 3),
                    Vec3(1, 2, 3 + 4.440892098500626e-16)};
  mesh.triangles = {{0, 1, 2}, {2, 3, 4}};
  const WeldedMesh welded = weld_coincident_vertices(mesh);
  EXPECT_EQ(welded.input_to_mesh, std::vector<std::int32_t>({0, 0, 1, 2, 3}));
  EXPECT_EQ(welded.merged_vertex_count, 1u);
  // The face whose corners became repeated is kept, for the analyzer to count as degenerate.
  EXPECT_EQ(welded.mesh.triangles, std::vector<Triangle>({{0, 0, 1}, {1, 2, 3}}));
}

TEST(Weld, GridSoupInReverseOrder) {
  // Many positions that differ in few bits, each listed twice: exercises hash collisions.
  constexpr int n = 200;
  TriangleMesh mesh;
  for (int pass = 0; pass < 2; ++pass)
    for (int i = 0; i < n * n; ++i) {
      const int k = pass == 0 ? i : n * n - 1 - i;
      mesh.positions.emplace_back(0.001 * (k % n), 0.001 * (k / n), 0.0);
    }
  mesh.triangles = {{0, 1, 2 * n * n - 1}};
  const WeldedMesh welded = weld_coincident_vertices(mesh);
  ASSERT_EQ(welded.mesh.positions.size(), std::size_t{n * n});
  EXPECT_EQ(welded.merged_vertex_count, std::size_t{n * n});
  for (int i = 0; i < n * n; ++i) {
    EXPECT_EQ(welded.input_to_mesh[i], i);
    ASSERT_EQ(welded.input_to_mesh[n * n + i], n * n - 1 - i);
  }
  EXPECT_EQ(welded.mesh.triangles, std::vector<Triangle>({{0, 1, 0}}));
}

}  // namespace
}  // namespace toonwater
