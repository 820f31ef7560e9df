// Connectivity (analyzer/topology.hpp): components, boundary and non-manifold detection on
// meshes whose answer is known by construction, faces with a repeated corner ignored, and
// orientation fixing that restores the outward winding of a closed surface.
#include "analyzer/topology.hpp"

#include "corpus/analytic_surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace toonwater {
namespace {

// `b` appended to `a`, its vertices moved by `offset`.
TriangleMesh joined(TriangleMesh a, const TriangleMesh& b, const Vec3& offset) {
  const auto base = static_cast<std::int32_t>(a.positions.size());
  for (const Vec3& p : b.positions) a.positions.push_back(p + offset);
  for (const Triangle& t : b.triangles)
    a.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  return a;
}

std::size_t count_kind(const MeshTopology& topo, VertexKind kind) {
  return static_cast<std::size_t>(std::count(topo.kind.begin(), topo.kind.end(), kind));
}

// Every edge of the mesh with how often it is traversed in each direction.
std::map<std::pair<std::int32_t, std::int32_t>, int> directed_edges(const TriangleMesh& mesh) {
  std::map<std::pair<std::int32_t, std::int32_t>, int> edges;
  for (const Triangle& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) ++edges[{t[c], t[(c + 1) % 3]}];
  return edges;
}

// Consistent: no directed edge is traversed twice (two neighbours running the same way).
bool consistently_oriented(const TriangleMesh& mesh) {
  for (const auto& [edge, count] : directed_edges(mesh))
    if (count > 1) return false;
  return true;
}

TEST(Topology, ClosedSurfacesAreAllInteriorWithTheirEulerCharacteristic) {
  // V − E + F = 2 for the sphere, 0 for the torus, with E = 3F/2 on a closed triangle mesh.
  for (const auto& [mesh, euler] :
       {std::pair{make_icosphere(3).mesh, 2}, std::pair{make_torus(24, 12).mesh, 0}}) {
    const MeshTopology topo = analyze_topology(mesh);
    EXPECT_EQ(count_components(mesh, topo), 1u);
    EXPECT_EQ(count_kind(topo, VertexKind::interior), mesh.positions.size());
    EXPECT_EQ(topo.boundary_edges, 0u);
    EXPECT_EQ(topo.nonmanifold_edges, 0u);
    EXPECT_EQ(topo.isolated_vertices, 0u);
    const auto v = static_cast<long>(mesh.positions.size());
    const auto f = static_cast<long>(mesh.triangles.size());
    EXPECT_EQ(v - 3 * f / 2 + f, euler);
  }
}

// The rows are built on every core; they must be what one pass in face order gives.
TEST(Topology, VertexFacesOfALargeMeshListEachVertexsFacesInOrder) {
  TriangleMesh mesh = make_wave_field(300, 0.1, 6.0, 1.0).mesh;        // 178k faces: several chunks
  mesh.triangles[1000] = {5, 5, 6};                                    // ignored: a repeated corner
  std::reverse(mesh.triangles.begin() + 50000, mesh.triangles.end());  // rows across chunks
  const VertexFaces vf = build_vertex_faces(mesh.positions.size(), mesh.triangles);
  std::vector<std::vector<std::int32_t>> expected(mesh.positions.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    if (!has_repeated_corner(mesh.triangles[f]))
      for (const std::int32_t v : mesh.triangles[f])
        expected[v].push_back(static_cast<std::int32_t>(f));
  ASSERT_EQ(vf.offsets.size(), mesh.positions.size() + 1);
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    const auto row = vf.of(static_cast<std::int32_t>(v));
    ASSERT_EQ(std::vector<std::int32_t>(row.begin(), row.end()), expected[v]) << v;
  }
  EXPECT_EQ(count_components(mesh, analyze_topology(mesh)), 1u);
}

TEST(Topology, AGridHasItsRimAsBoundary) {
  constexpr int n = 9;
  const TriangleMesh grid = make_saddle(n).mesh;
  const MeshTopology topo = analyze_topology(grid);
  EXPECT_EQ(count_components(grid, topo), 1u);
  EXPECT_EQ(topo.boundary_vertices, 4u * (n - 1));
  EXPECT_EQ(topo.boundary_edges, 4u * (n - 1));
  EXPECT_EQ(count_kind(topo, VertexKind::interior), std::size_t((n - 2) * (n - 2)));
  EXPECT_EQ(topo.nonmanifold_vertices, 0u);
  // The boundary is exactly the vertices on the square's edges.
  for (std::size_t v = 0; v < grid.positions.size(); ++v) {
    const Vec3& p = grid.positions[v];
    const bool on_rim = std::max(std::abs(p.x()), std::abs(p.y())) > 0.5 - 1e-12;
    EXPECT_EQ(topo.kind[v] == VertexKind::boundary, on_rim) << "vertex " << v;
  }
  // The faces of each vertex are the faces that contain it, and no others.
  for (std::size_t v = 0; v < grid.positions.size(); ++v) {
    std::size_t containing = 0;
    for (const Triangle& t : grid.triangles)
      containing += std::count(t.begin(), t.end(), static_cast<std::int32_t>(v));
    EXPECT_EQ(topo.vertex_faces.of(static_cast<std::int32_t>(v)).size(), containing);
  }
}

TEST(Topology, CountsComponentsAndIsolatedVertices) {
  TriangleMesh two = joined(make_icosphere(1).mesh, make_icosphere(1).mesh, Vec3(5, 0, 0));
  two = joined(two, make_saddle(5).mesh, Vec3(0, 9, 0));
  two.positions.emplace_back(0, 0, 20);  // in no face
  const MeshTopology topo = analyze_topology(two);
  EXPECT_EQ(count_components(two, topo), 3u);
  EXPECT_EQ(topo.isolated_vertices, 1u);
  EXPECT_EQ(topo.kind.back(), VertexKind::isolated);
  EXPECT_EQ(topo.boundary_edges, 16u);  // the 5 × 5 grid's rim
}

TEST(Topology, FinsAndBowtiesAreNonManifold) {
  // Three faces on the edge 0–1: a fin.
  TriangleMesh fin;
  fin.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0, 0, 1)};
  fin.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  MeshTopology topo = analyze_topology(fin);
  EXPECT_EQ(topo.nonmanifold_edges, 1u);
  EXPECT_EQ(topo.kind[0], VertexKind::nonmanifold);
  EXPECT_EQ(topo.kind[1], VertexKind::nonmanifold);
  EXPECT_EQ(topo.kind[2], VertexKind::boundary);
  EXPECT_EQ(topo.boundary_edges, 6u);

  // Two triangles sharing only vertex 0: two fans at one point.
  TriangleMesh bowtie;
  bowtie.positions = {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(1, -1, 0), Vec3(-1, 1, 0),
                      Vec3(-1, -1, 0)};
  bowtie.triangles = {{0, 2, 1}, {0, 3, 4}};
  topo = analyze_topology(bowtie);
  EXPECT_EQ(topo.kind[0], VertexKind::nonmanifold);
  EXPECT_EQ(topo.nonmanifold_vertices, 1u);
  EXPECT_EQ(topo.nonmanifold_edges, 0u);
  EXPECT_EQ(count_components(bowtie, topo), 1u);
}

TEST(Topology, FacesWithARepeatedCornerAreIgnored) {
  EXPECT_TRUE(has_repeated_corner({3, 3, 1}));
  EXPECT_TRUE(has_repeated_corner({1, 2, 1}));
  EXPECT_FALSE(has_repeated_corner({0, 1, 2}));
  TriangleMesh mesh = make_icosphere(1).mesh;
  const MeshTopology before = analyze_topology(mesh);
  mesh.triangles.push_back({0, 0, 1});
  mesh.triangles.push_back({2, 5, 5});
  const MeshTopology after = analyze_topology(mesh);
  EXPECT_EQ(after.vertex_faces.face_indices, before.vertex_faces.face_indices);
  EXPECT_EQ(after.boundary_edges, 0u);
  EXPECT_EQ(after.nonmanifold_edges, 0u);
  EXPECT_EQ(count_kind(after, VertexKind::interior), mesh.positions.size());

  TriangleMesh only_degenerate;
  only_degenerate.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0)};
  only_degenerate.triangles = {{0, 0, 1}};
  const MeshTopology none = analyze_topology(only_degenerate);
  EXPECT_EQ(none.isolated_vertices, 2u);
  EXPECT_EQ(count_components(only_degenerate, none), 0u);
}

TEST(Topology, OrientationFixingRestoresTheMajorityWinding) {
  const TriangleMesh sphere = make_icosphere(2).mesh;  // outward, consistent
  ASSERT_TRUE(consistently_oriented(sphere));
  TriangleMesh mesh = sphere;
  const std::vector<std::size_t> flipped_faces = {0, 7, 42, 100, 251};
  for (std::size_t f : flipped_faces) std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
  ASSERT_FALSE(consistently_oriented(mesh));
  EXPECT_EQ(orient_consistently(mesh, analyze_topology(mesh)), flipped_faces.size());
  EXPECT_EQ(mesh.triangles, sphere.triangles);  // the five faces turned back, outward again

  // Most faces turned inward: the inward winding is kept and the five outward ones follow it.
  mesh = sphere;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    if (std::find(flipped_faces.begin(), flipped_faces.end(), f) == flipped_faces.end())
      std::swap(mesh.triangles[f][1], mesh.triangles[f][2]);
  EXPECT_EQ(orient_consistently(mesh, analyze_topology(mesh)), flipped_faces.size());
  EXPECT_TRUE(consistently_oriented(mesh));
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f)
    EXPECT_EQ(mesh.triangles[f][1], sphere.triangles[f][2]) << "face " << f << " not inward";

  // A consistent mesh is left alone; components are oriented each on its own.
  TriangleMesh two = joined(sphere, sphere, Vec3(4, 0, 0));
  std::swap(two.triangles.back()[1], two.triangles.back()[2]);
  const TriangleMesh expected = joined(sphere, sphere, Vec3(4, 0, 0));
  EXPECT_EQ(orient_consistently(two, analyze_topology(two)), 1u);
  EXPECT_EQ(two.triangles, expected.triangles);
  EXPECT_EQ(orient_consistently(two, analyze_topology(two)), 0u);
}

}  // namespace
}  // namespace toonwater
