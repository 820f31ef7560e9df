// `toonwater analyze MESH --maps DIR`: the files, the summary line, and bad options.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/obj_writer.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

TEST(MapsCli, AnalyzeWritesMapsAndPrintsTheirRanges) {
  test::ScratchDir dir;
  write_obj(dir / "wave_0007.obj", make_wave_field(61, 0.1, 6.0).mesh);
  const auto result = test::run_toonwater({"analyze", (dir / "wave_0007.obj").string(), "--up", "z",
                                           "--maps", (dir / "maps").string(), "--maps-size", "96"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* name :
       {"wave_0007.exr", "wave_0007_K.png", "wave_0007_H.png", "wave_0007_label.png"})
    EXPECT_TRUE(fs::exists(dir / "maps" / name)) << name;
  const test::ReadImage exr = test::read_image(dir / "maps" / "wave_0007.exr");
  EXPECT_EQ(std::max(exr.spec.width, exr.spec.height), 96);

  // The summary prints the same ranges as the metadata holds (to 6 digits).
  const double k_range = std::stod(exr.spec.get_string_attribute("toonwater:K_range"));
  char expected[64];
  std::snprintf(expected, sizeof expected, "K \u00b1%.6g", k_range);
  EXPECT_NE(result.output.find(expected), std::string::npos) << result.output;
}

TEST(MapsCli, GivenBoxSetsTheExtent) {
  test::ScratchDir dir;
  write_obj(dir / "w.obj", make_wave_field(41, 0.1, 6.0).mesh);
  const auto result =
      test::run_toonwater({"analyze", (dir / "w.obj").string(), "--up", "z", "--maps",
                           dir.path().string(), "--maps-size", "50", "--maps-box", "-2,-1,2,1"});
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const test::ReadImage exr = test::read_image(dir / "w.exr");
  EXPECT_EQ(exr.spec.width, 50);
  EXPECT_EQ(exr.spec.height, 25);
  EXPECT_EQ(exr.at(0, 12, "A"), 0.0f);   // x = −2 lies off the [−1, 1]² wave field
  EXPECT_EQ(exr.at(25, 12, "A"), 1.0f);  // the centre lies on it
}

TEST(MapsCli, BadMapOptionsFailWithoutWritingMaps) {
  test::ScratchDir dir;
  write_obj(dir / "w.obj", make_wave_field(21, 0.1).mesh);
  for (const std::vector<std::string>& extra :
       {std::vector<std::string>{"--maps-size", "0"}, {"--maps-box", "1,2,3"}}) {
    std::vector<std::string> args{"analyze", (dir / "w.obj").string(), "--maps",
                                  (dir / "maps").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto result = test::run_toonwater(args);
    EXPECT_NE(result.exit_code, 0) << extra[0];
    EXPECT_NE(result.output.find("error"), std::string::npos) << result.output;
    EXPECT_FALSE(fs::exists(dir / "maps")) << extra[0];
  }
  // A file where the directory should be: a one-line error naming it.
  test::write_text(dir / "taken", "not a directory");
  const auto result = test::run_toonwater(
      {"analyze", (dir / "w.obj").string(), "--up", "z", "--maps", (dir / "taken").string()});
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find((dir / "taken").string()), std::string::npos) << result.output;
  EXPECT_EQ(test::read_text(dir / "taken"), "not a directory");
}

}  // namespace
}  // namespace toonwater
