// The OBJ writer (analyzer/obj_writer.hpp): exact coordinates, 1-based faces, the comment line,
// and no file for a mesh with a NaN or infinite coordinate.
#include "analyzer/obj_writer.hpp"

#include "analyzer/mesh_reader.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace toonwater {
namespace {

TriangleMesh awkward_tetrahedron() {
  TriangleMesh m;
  m.positions = {Vec3(1.0 / 3.0, 0.1, -2.5e-7), Vec3(123456789.123456789, -1e300, 1e-300),
                 Vec3(std::nextafter(1.0, 2.0), -0.0, 6.02214076e23), Vec3(0, 0, 1)};
  m.triangles = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
  return m;
}

TEST(ObjWriter, CoordinatesReadBackToTheBit) {
  const TriangleMesh m = awkward_tetrahedron();
  test::ScratchDir dir;
  write_obj(dir / "m.obj", m);
  const InputMesh back = read_mesh(dir / "m.obj");
  ASSERT_EQ(back.mesh.positions.size(), m.positions.size());
  for (std::size_t i = 0; i < m.positions.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(back.mesh.positions[i][k], m.positions[i][k]) << "vertex " << i << " axis " << k;
  EXPECT_EQ(back.mesh.triangles, m.triangles);
}

TEST(ObjWriter, WritesTheShortestExactDecimalsAndOneBasedFaces) {
  TriangleMesh m;
  m.positions = {Vec3(0.1, 2, -0.5), Vec3(1.0 / 3.0, 0, 1e-9), Vec3(0, 1, 0)};
  m.triangles = {{0, 1, 2}};
  EXPECT_EQ(obj_text(m), "v 0.1 2 -0.5\nv 0.3333333333333333 0 1e-09\nv 0 1 0\nf 1 2 3\n");
  EXPECT_EQ(obj_text(m, "frame 7").substr(0, 10), "# frame 7\n");
}

TEST(ObjWriter, RefusesNonFiniteCoordinates) {
  TriangleMesh m = awkward_tetrahedron();
  m.positions[3].y() = std::nan("");
  EXPECT_THROW(obj_text(m), std::invalid_argument);
  m.positions[3].y() = std::numeric_limits<double>::infinity();
  test::ScratchDir dir;
  EXPECT_THROW(write_obj(dir / "m.obj", m), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir / "m.obj"));
}

}  // namespace
}  // namespace toonwater
