// Two-pass sequence maps from files: one view and one colour range shared by every frame.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/obj_writer.hpp"
#include "analyzer/maps/sequence_maps.hpp"
#include "analyzer/mesh_reader.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>


namespace toonwater {
namespace {

namespace fs = std::filesystem;

TEST(SequenceMaps, FramesShareViewAndRange) {
  test::ScratchDir dir;
  // A quiet frame over [−1, 1]² and a loud one over [−1.5, 1.5]²: the view covers both.
  write_obj(dir / "water_0001.obj", make_wave_field(61, 0.03, 6.0, 1.0).mesh);
  write_obj(dir / "water_0002.obj", make_wave_field(91, 0.1, 6.0, 1.5).mesh);
  AnalyzeOptions options;
  options.flow.up = Axis::z;
  std::size_t calls = 0;
  const SequenceMaps maps = write_sequence_maps(
      {dir / "water_0001.obj", dir / "water_0002.obj"}, options, MapOptions{}, dir / "maps", true, nullptr,
      [&](std::size_t done, std::size_t total) {
        EXPECT_EQ(done, ++calls);
        EXPECT_EQ(total, 2u);
      });
  EXPECT_EQ(maps.frames, 2u);
  EXPECT_EQ(calls, 2u);
  EXPECT_LE(maps.view.box.u_min, -1.5);
  EXPECT_GE(maps.view.box.u_max, 1.5);

  MapPlanner quiet(Axis::z);
  quiet.add(analyze_mesh(read_mesh(dir / "water_0001.obj").mesh, options));
  EXPECT_GT(maps.ranges.mean, quiet.ranges().mean);  // not the quiet frame's own range

  for (const char* name : {"water_0001", "water_0002"}) {
    const test::ReadImage exr = test::read_image(dir / "maps" / (std::string(name) + ".exr"));
    const test::ReadImage png = test::read_image(dir / "maps" / (std::string(name) + "_K.png"));
    EXPECT_EQ(exr.spec.width, maps.view.width) << name;
    EXPECT_EQ(exr.spec.height, maps.view.height) << name;
    EXPECT_EQ(std::stod(exr.spec.get_string_attribute("toonwater:H_range")), maps.ranges.mean);
    EXPECT_EQ(std::stod(png.spec.get_string_attribute("toonwater:K_range")), maps.ranges.gaussian);
  }
  // The quiet frame covers only the middle of the shared view.
  const test::ReadImage first = test::read_image(dir / "maps" / "water_0001.exr");
  EXPECT_EQ(first.at(0, 0, "A"), 0.0f);
  EXPECT_EQ(first.at(maps.view.width / 2, maps.view.height / 2, "A"), 1.0f);
}

TEST(SequenceMaps, UnreadableFrameIsAnInputError) {
  test::ScratchDir dir;
  test::write_text(dir / "water_0001.obj", "v 0 0 0\nf 1 2 3\n");
  AnalyzeOptions options;
  EXPECT_THROW(write_sequence_maps({dir / "water_0001.obj"}, options, MapOptions{}, dir / "maps"),
               InputError);
  EXPECT_FALSE(fs::exists(dir / "maps"));
}

}  // namespace
}  // namespace toonwater
