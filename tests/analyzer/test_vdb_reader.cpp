// OpenVDB level sets read as meshes (analyzer/readers/vdb/vdb_module.hpp): which grid is
// meshed, that the mesh is the level set's zero surface with its normals out of the liquid, and
// the errors that name the grids a file holds.
#include "analyzer/mesh_reader.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numbers>
#include <string>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

openvdb::FloatGrid::Ptr sphere(const std::string& name, double radius, const openvdb::Vec3f& centre,
                               double voxel) {
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(
      static_cast<float>(radius), centre, static_cast<float>(voxel));
  grid->setName(name);
  return grid;
}

openvdb::FloatGrid::Ptr fog(const std::string& name) {
  auto grid = openvdb::FloatGrid::create(0.0f);
  grid->setName(name);
  grid->setGridClass(openvdb::GRID_FOG_VOLUME);
  grid->tree().setValue(openvdb::Coord(1, 2, 3), 1.0f);
  return grid;
}

void write_vdb(const fs::path& path, const openvdb::GridPtrVec& grids) {
  openvdb::io::File file(path.string());
  file.write(grids);
  file.close();
}

// The volume a closed mesh encloses, positive when its faces turn outward.
double signed_volume(const TriangleMesh& mesh) {
  double six_v = 0;
  for (const Triangle& t : mesh.triangles)
    six_v += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return six_v / 6.0;
}

// The message of the InputError that reading `path` throws; a test failure when it reads.
std::string read_error(const fs::path& path, const LevelSetOptions& options = {}) {
  try {
    read_mesh(path, options);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << path << " was read";
  return {};
}

TEST(VdbReader, ASphereLevelSetIsItsZeroSurfaceFacingOut) {
  ScratchDir dir;
  const openvdb::Vec3f centre(0.3f, -0.2f, 0.5f);
  write_vdb(dir / "ball.vdb", {sphere("surface", 1.0, centre, 0.05)});
  const InputMesh read = read_mesh(dir / "ball.vdb");
  ASSERT_GT(read.mesh.triangles.size(), 1000u);
  const Vec3 c(centre.x(), centre.y(), centre.z());
  for (const Vec3& p : read.mesh.positions) EXPECT_NEAR((p - c).norm(), 1.0, 0.01);
  EXPECT_NEAR(signed_volume(read.mesh), 4.0 / 3.0 * std::numbers::pi, 0.02 * 4.0)
      << "a negative volume: the faces turn into the liquid";
}

TEST(VdbReader, TheGridIsSurfaceThenPhiThenTheOnlyLevelSet) {
  ScratchDir dir;
  // Mantaflow's data cache: phi beside fog volumes; the ball of radius 1 is phi.
  write_vdb(dir / "data.vdb", {fog("density"), sphere("phi", 1.0, {0, 0, 0}, 0.1),
                               sphere("other", 0.5, {0, 0, 0}, 0.1)});
  EXPECT_NEAR(read_mesh(dir / "data.vdb").mesh.positions.front().norm(), 1.0, 0.02);
  write_vdb(dir / "both.vdb",
            {sphere("phi", 0.5, {0, 0, 0}, 0.05), sphere("surface", 1.0, {0, 0, 0}, 0.05)});
  EXPECT_NEAR(read_mesh(dir / "both.vdb").mesh.positions.front().norm(), 1.0, 0.02);
  write_vdb(dir / "only.vdb", {fog("density"), sphere("liquid", 0.5, {0, 0, 0}, 0.05)});
  EXPECT_NEAR(read_mesh(dir / "only.vdb").mesh.positions.front().norm(), 0.5, 0.02);
}

TEST(VdbReader, AGridNamedIsMeshedAndAdaptivityMergesFlatCells) {
  ScratchDir dir;
  write_vdb(dir / "two.vdb",
            {sphere("a", 1.0, {0, 0, 0}, 0.05), sphere("b", 0.5, {0, 0, 0}, 0.05), fog("density")});
  EXPECT_NEAR(read_mesh(dir / "two.vdb", {"b", 0.0}).mesh.positions.front().norm(), 0.5, 0.02);
  const InputMesh fine = read_mesh(dir / "two.vdb", {"a", 0.0});
  const InputMesh coarse = read_mesh(dir / "two.vdb", {"a", 1.0});
  EXPECT_NEAR(fine.mesh.positions.front().norm(), 1.0, 0.02);
  EXPECT_LT(coarse.mesh.triangles.size(), fine.mesh.triangles.size());
  // Merged cells cut the sphere's corners, but the faces still turn outward.
  EXPECT_GT(signed_volume(coarse.mesh), 0.8 * 4.0 / 3.0 * std::numbers::pi);
  for (const std::string wrong : {"c", "density"}) {
    const std::string message = read_error(dir / "two.vdb", {wrong, 0.0});
    EXPECT_NE(message.find("two.vdb: "), std::string::npos) << message;
    EXPECT_NE(message.find("'" + wrong + "'"), std::string::npos) << message;
  }
}

TEST(VdbReader, NoLevelSetOrTwoAreErrorsNamingTheGrids) {
  ScratchDir dir;
  write_vdb(dir / "fog.vdb", {fog("density")});
  const std::string fog_error = read_error(dir / "fog.vdb");
  EXPECT_NE(fog_error.find("fog.vdb: no level-set grid"), std::string::npos) << fog_error;
  EXPECT_NE(fog_error.find("'density' (float, fog volume)"), std::string::npos) << fog_error;
  write_vdb(dir / "two.vdb", {sphere("a", 1.0, {0, 0, 0}, 0.1), sphere("b", 1.0, {0, 0, 0}, 0.1)});
  const std::string two_error = read_error(dir / "two.vdb");
  EXPECT_NE(two_error.find("more than one level-set grid"), std::string::npos) << two_error;
  write_text(dir / "text.vdb", "not a vdb file\n");
  EXPECT_THROW(read_mesh(dir / "text.vdb"), InputError);
  // A level set without a zero crossing holds no surface: an empty frame.
  auto empty = openvdb::FloatGrid::create(0.3f);
  empty->setName("surface");
  empty->setGridClass(openvdb::GRID_LEVEL_SET);
  write_vdb(dir / "empty.vdb", {empty});
  EXPECT_THROW(read_mesh(dir / "empty.vdb"), EmptyMeshError);
}

// A file cut short anywhere in the grid it needs is one short line, whatever OpenVDB read in
// place of a type name.
TEST(VdbReader, ATruncatedFileIsOneShortLine) {
  ScratchDir dir;
  // The grid it needs last, so that every cut falls before its end.
  write_vdb(dir / "whole.vdb",
            {fog("density"), fog("heat"), sphere("surface", 1.0, {0, 0, 0}, 0.1)});
  const std::string bytes = read_text(dir / "whole.vdb");
  for (double kept = 0.01; kept < 1.0; kept += 0.02) {
    SCOPED_TRACE(kept);
    const auto length = static_cast<std::size_t>(kept * static_cast<double>(bytes.size()));
    write_text(dir / "cut.vdb", bytes.substr(0, length));
    const std::string message = read_error(dir / "cut.vdb");
    EXPECT_NE(message.find("cut.vdb: "), std::string::npos) << message;
    EXPECT_LT(message.size(), 400u) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
}

// A level set holds distances: a NaN or infinite one (a damaged file, a solver that blew up),
// in a voxel or in the background, is refused with one line naming the file and where it is.
TEST(VdbReader, ANonFiniteDistanceIsAnErrorNamingWhereItIs) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const float bad : {nan, inf, -inf})
    for (const bool background : {false, true}) {
      SCOPED_TRACE(std::to_string(bad) + (background ? " background" : " voxel"));
      ScratchDir dir;
      auto grid = sphere("surface", 1.0, {0, 0, 0}, 0.1);
      if (background)
        grid->tree().root().setBackground(bad, true);
      else
        grid->tree().setValue(openvdb::Coord(10, 0, 0), bad);  // on the surface, x = 1
      write_vdb(dir / "bad.vdb", {grid});
      const std::string message = read_error(dir / "bad.vdb");
      EXPECT_NE(message.find("bad.vdb: grid 'surface' "), std::string::npos) << message;
      if (!background) {
        EXPECT_NE(message.find("voxel (10, 0, 0)"), std::string::npos) << message;
      }
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
}

// OpenVDB states each grid's size in memory in the file: one larger than the machine (a dense
// grid of zeros is small on disk) is refused before it is read, with one line naming the file.
TEST(VdbReader, AGridLargerThanTheMachinesMemoryIsRefusedBeforeItIsRead) {
  ScratchDir dir;
  write_vdb(dir / "huge.vdb", {sphere("surface", 1.0, {0, 0, 0}, 0.1)});
  std::string bytes = read_text(dir / "huge.vdb");
  // The metadata's layout: the name, the type name "int64" (each after its 4-byte length), the
  // value's size (8), then the value, little-endian.
  const std::string key = "file_mem_bytes";
  const std::size_t at = bytes.find(key);
  ASSERT_NE(at, std::string::npos) << "OpenVDB wrote no size";
  const std::size_t value = at + key.size() + 4 + 5 + 4;
  ASSERT_EQ(bytes.substr(at + key.size() + 4, 5), "int64");
  const std::int64_t petabyte = std::int64_t{1} << 50;
  std::memcpy(&bytes[value], &petabyte, sizeof petabyte);
  write_text(dir / "huge.vdb", bytes);
  const std::string message = read_error(dir / "huge.vdb");
  EXPECT_NE(message.find("huge.vdb: grid 'surface' takes 1048576 GiB in memory"), std::string::npos)
      << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}

}  // namespace
}  // namespace toonwater::test
