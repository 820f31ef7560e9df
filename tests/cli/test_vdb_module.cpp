// The toonwater program and its OpenVDB module (analyzer/readers/vdb/vdb_module.hpp): the
// program links no OpenVDB; without toonwater-vdb.so beside it every other format reads, and a
// .vdb file fails with one line naming the module and exit code 6 (incomplete installation).
// With it, a level set is analysed and a sequence of them becomes a scene.
#include "cli/exit_codes.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <openvdb/openvdb.h>
#include <openvdb/tools/LevelSetSphere.h>

#include <cstdio>
#include <filesystem>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* vdb_module_name = "toonwater-vdb.so";

void write_ball(const fs::path& path, float radius) {
  openvdb::initialize();
  auto grid = openvdb::tools::createLevelSetSphere<openvdb::FloatGrid>(radius, {0, 0, 0}, 0.05f);
  grid->setName("surface");
  openvdb::io::File file(path.string());
  file.write({grid});
  file.close();
}

TEST(VdbModule, TheProgramLinksNoOpenVdb) {
  const std::string listed = libraries_the_program_loads();
  ASSERT_NE(listed.find("libstdc++"), std::string::npos) << listed;
  EXPECT_EQ(listed.find("openvdb"), std::string::npos) << listed;
}

TEST(VdbModule, WithoutItOnlyVdbFilesFailAndWithItTheyBecomeScenes) {
  ScratchDir dir;
  fs::copy_file(TOONWATER_EXECUTABLE, dir / "toonwater");
  write_text(dir / "water.obj", "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n");
  write_ball(dir / "ball_0001.vdb", 1.0f);
  write_ball(dir / "ball_0002.vdb", 0.9f);

  CommandResult r = run_program(dir / "toonwater", {"analyze", (dir / "water.obj").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::success) << r.output;
  r = run_program(dir / "toonwater", {"analyze", (dir / "ball_0001.vdb").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::incomplete_install) << r.output;
  EXPECT_NE(r.output.find((dir.path() / vdb_module_name).string()), std::string::npos) << r.output;

  fs::copy_file(fs::path(TOONWATER_EXECUTABLE).parent_path() / vdb_module_name,
                dir / vdb_module_name);
  r = run_program(dir / "toonwater", {"analyze", (dir / "ball_0001.vdb").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::success) << r.output;
  EXPECT_NE(r.output.find("boundary 0, non-manifold 0"), std::string::npos)
      << "a closed surface: " << r.output;
  r = run_program(dir / "toonwater", {"povgen", "--water", (dir / "ball_####.vdb").string(),
                                      "--out", (dir / "scene").string()});
  ASSERT_EQ(r.exit_code, cli::exit_code::success) << r.output;
  EXPECT_TRUE(fs::exists(dir / "scene" / "water_0001.inc"));
  EXPECT_TRUE(fs::exists(dir / "scene" / "water_0002.inc"));

  // --grid and --adaptivity: for a level set only, the grid named, in range.
  r = run_program(dir / "toonwater",
                  {"analyze", (dir / "ball_0001.vdb").string(), "--grid", "nope"});
  EXPECT_EQ(r.exit_code, cli::exit_code::bad_input) << r.output;
  EXPECT_NE(r.output.find("no grid named 'nope'; its grids: 'surface' (float, level set)"),
            std::string::npos)
      << r.output;
  r = run_program(dir / "toonwater",
                  {"analyze", (dir / "water.obj").string(), "--grid", "surface"});
  EXPECT_EQ(r.exit_code, cli::exit_code::bad_input) << r.output;
  EXPECT_NE(r.output.find("--grid and --adaptivity are for .vdb level sets"), std::string::npos)
      << r.output;
  r = run_program(dir / "toonwater",
                  {"povgen", "--water", (dir / "ball_####.vdb").string(), "--out",
                   (dir / "coarse").string(), "--grid", "surface", "--adaptivity", "2"});
  EXPECT_EQ(r.exit_code, cli::exit_code::bad_input) << r.output;
  r = run_program(dir / "toonwater",
                  {"povgen", "--water", (dir / "ball_####.vdb").string(), "--out",
                   (dir / "coarse").string(), "--grid", "surface", "--adaptivity", "0.5"});
  EXPECT_EQ(r.exit_code, cli::exit_code::success) << r.output;
}

}  // namespace
}  // namespace toonwater::test
