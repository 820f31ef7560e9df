// The toonwater program and its image module (images/image_codec.hpp): the program links no
// OpenImageIO; without toonwater-images.so beside it, every command that writes no image works,
// and one that does fails before any work with one line naming the module and exit code 6
// (incomplete installation), writing nothing.
#include "cli/exit_codes.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr const char* image_module_name = "toonwater-images.so";

void write_square(const fs::path& path) {
  write_text(path, "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nf 1 2 3\nf 1 3 4\n");
}

TEST(ImageModule, TheProgramLinksNoOpenImageIO) {
  const std::string listed = libraries_the_program_loads();
  ASSERT_NE(listed.find("libstdc++"), std::string::npos) << listed;
  EXPECT_EQ(listed.find("OpenImageIO"), std::string::npos) << listed;
  EXPECT_TRUE(fs::exists(fs::path(TOONWATER_EXECUTABLE).parent_path() / image_module_name));
}

TEST(ImageModule, WithoutItOnlyTheCommandsThatWriteImagesFail) {
  ScratchDir dir;
  fs::copy_file(TOONWATER_EXECUTABLE, dir / "toonwater");
  write_square(dir / "water.obj");

  CommandResult r = run_program(dir / "toonwater", {"analyze", (dir / "water.obj").string(),
                                                    "--csv", (dir / "water.csv").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::success) << r.output;
  EXPECT_TRUE(fs::exists(dir / "water.csv"));

  r = run_program(dir / "toonwater",
                  {"analyze", (dir / "water.obj").string(), "--csv", (dir / "both.csv").string(),
                   "--maps", (dir / "maps").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::incomplete_install) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_EQ(r.output.rfind("toonwater: error: ", 0), 0u) << r.output;
  EXPECT_NE(r.output.find((dir.path() / image_module_name).string()), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "both.csv"));
  EXPECT_FALSE(fs::exists(dir / "maps"));

  r = run_program(dir / "toonwater",
                  {"povgen", "--water", (dir / "water.obj").string(), "--out",
                   (dir / "scene").string(), "--maps", (dir / "scene_maps").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::incomplete_install) << r.output;
  EXPECT_FALSE(fs::exists(dir / "scene"));

  // With the module beside it, the same copy writes the maps.
  fs::copy_file(fs::path(TOONWATER_EXECUTABLE).parent_path() / image_module_name,
                dir / image_module_name);
  r = run_program(dir / "toonwater",
                  {"analyze", (dir / "water.obj").string(), "--maps", (dir / "maps").string()});
  EXPECT_EQ(r.exit_code, cli::exit_code::success) << r.output;
  EXPECT_TRUE(fs::exists(dir / "maps" / "water_K.png"));
}

}  // namespace
}  // namespace toonwater::test
