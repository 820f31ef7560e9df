// Free-surface selection: upward faces, one ring in from the walls, patches that are too deep
// or too small dropped.
#include "analyzer/flow_regions.hpp"
#include "analyzer/free_surface.hpp"
#include "analyzer/topology.hpp"
#include "tests/analyzer/water_meshes.hpp"

#include <gtest/gtest.h>

namespace toonwater::test {
namespace {

FreeSurface free_surface_of(const TriangleMesh& mesh, FreeSurfaceOptions options = {}) {
  options.up = Axis::z;
  return select_free_surface(mesh, options);
}

// A square step of the given height within radius 0.3 of the centre: on a 0.05 grid its
// sides are nearly vertical, so the step's top is a patch of its own.
HeightFunction step(double height) {
  return [height](double x, double y) { return std::hypot(x, y) < 0.3 ? height : 0.0; };
}

std::size_t selected_inside(const TriangleMesh& m, const FreeSurface& s, double radius) {
  std::size_t count = 0;
  for (std::size_t v = 0; v < m.positions.size(); ++v)
    count += s.selected[v] && std::hypot(m.positions[v].x(), m.positions[v].y()) < radius &&
             m.positions[v].z() > -0.5;
  return count;
}

TEST(FreeSurface, CavityFloorBelowTheRestLevelIsDropped) {
  const TriangleMesh m = tank(41, step(-0.3));  // 6 edge lengths deep
  const FreeSurface s = free_surface_of(m);
  EXPECT_EQ(s.patches_dropped, 1u);
  EXPECT_EQ(selected_inside(m, s, 0.25), 0u);
  EXPECT_DOUBLE_EQ(s.rest_height, 0.0);
}

TEST(FreeSurface, RaisedPatchIsKept) {
  const TriangleMesh m = tank(41, step(0.3));
  const FreeSurface s = free_surface_of(m);
  EXPECT_EQ(s.patches_dropped, 0u);
  EXPECT_EQ(s.patches_kept, 2u);
  EXPECT_GT(selected_inside(m, s, 0.25), 10u);
}

TEST(FreeSurface, DropletsAreKeptAboveAGivenSize) {
  TriangleMesh m = tank(41, [](double, double) { return 0.0; });
  // A detached droplet (a separate closed sphere) above the water.
  const AnalyticSurface drop = make_icosphere(3, 0.2);
  const auto offset = static_cast<std::int32_t>(m.positions.size());
  for (const Vec3& p : drop.mesh.positions) m.positions.push_back(p + Vec3(0, 0, 0.6));
  for (const Triangle& t : drop.mesh.triangles)
    m.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  auto droplet_vertices = [&](const FreeSurface& s) {
    std::size_t count = 0;
    for (std::size_t v = static_cast<std::size_t>(offset); v < m.positions.size(); ++v)
      count += s.selected[v];
    return count;
  };
  const FreeSurface kept = free_surface_of(m);
  EXPECT_GT(droplet_vertices(kept), 16u);  // its upper cap
  FreeSurfaceOptions options;
  options.min_patch_vertices = 10000;
  const FreeSurface dropped = free_surface_of(m, options);
  EXPECT_EQ(droplet_vertices(dropped), 0u);
  EXPECT_EQ(dropped.patches_dropped, 1u);
  EXPECT_EQ(dropped.vertices + droplet_vertices(kept), kept.vertices);
}

TEST(FreeSurface, SteepFacesAreNotFreeSurface) {
  // A 70° slope everywhere: nothing faces up enough.
  const TriangleMesh m = height_field(21, [](double x, double) { return 2.75 * x; });
  EXPECT_EQ(free_surface_of(m).vertices, 0u);
  const TriangleMesh gentle = height_field(21, [](double x, double) { return 1.5 * x; });  // 56°
  EXPECT_EQ(free_surface_of(gentle).vertices, 21u * 21u);
}

// `inside` is the free surface less its border ring: exactly the selected vertices all of
// whose faces have every corner selected, here where a cavity floor is dropped and a raised
// patch kept, on a mesh large enough to be marked on several cores.
TEST(FreeSurface, InsideIsTheFreeSurfaceLessItsBorderRing) {
  for (const double step_height : {-0.3, 0.3}) {
    const TriangleMesh m = tank(301, step(step_height));
    const FreeSurface s = free_surface_of(m);
    const VertexFaces faces = build_vertex_faces(m.positions.size(), m.triangles);
    std::size_t inside = 0, border = 0;
    for (std::size_t v = 0; v < m.positions.size(); ++v) {
      bool expected = s.selected[v];
      for (const std::int32_t f : faces.of(static_cast<std::int32_t>(v)))
        for (const std::int32_t corner : m.triangles[f]) expected = expected && s.selected[corner];
      ASSERT_EQ(s.inside[v], expected) << "vertex " << v << ", step " << step_height;
      inside += expected;
      border += s.selected[v] && !expected;
    }
    EXPECT_GT(inside, 0u);
    EXPECT_GT(border, 4u * 300u);  // the walls' ring and the step's
  }
}

TEST(FreeSurface, EdgeLengthIsTheMedianEdgeLength) {
  for (const int n : {21, 301}) {
    const TriangleMesh m = tank(n, bump(0.2, 0.0, 0.0, 0.3));
    EXPECT_EQ(free_surface_of(m).edge_length, median_edge_length(m)) << n;
  }
}

// Two separate flat sheets of the same size, sheet A's first vertex first and all its others
// after sheet B's: the rest level is A's height, that of the patch whose first vertex comes
// first, although B's vertices (and its union-find root) come before most of A's.
TEST(FreeSurface, OfEqualLargestPatchesTheOneFirstInVertexOrderSetsTheRestLevel) {
  for (const double a_height : {0.5, 0.0}) {
    const TriangleMesh a = height_field(31, [a_height](double, double) { return a_height; });
    const TriangleMesh b = height_field(31, [a_height](double, double) { return 0.5 - a_height; });
    const auto size = static_cast<std::int32_t>(a.positions.size());
    auto a_index = [size](std::int32_t v) { return v == 0 ? 0 : size + v; };
    auto b_index = [](std::int32_t v) { return 1 + v; };
    TriangleMesh m;
    m.positions.resize(2 * static_cast<std::size_t>(size));
    for (std::int32_t v = 0; v < size; ++v) {
      m.positions[a_index(v)] = a.positions[v];
      m.positions[b_index(v)] = b.positions[v];
    }
    for (const Triangle& t : a.triangles)  // vertex 0 never a face's first corner: not A's root
      m.triangles.push_back(t[0] == 0 ? Triangle{a_index(t[1]), a_index(t[2]), a_index(t[0])}
                                      : Triangle{a_index(t[0]), a_index(t[1]), a_index(t[2])});
    for (const Triangle& t : b.triangles)
      m.triangles.push_back({b_index(t[0]), b_index(t[1]), b_index(t[2])});
    const FreeSurface s = free_surface_of(m);
    EXPECT_EQ(s.patches_kept + s.patches_dropped, 2u);
    EXPECT_EQ(s.rest_height, a_height);
  }
}

}  // namespace
}  // namespace toonwater::test
