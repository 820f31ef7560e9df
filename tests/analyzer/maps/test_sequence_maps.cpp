// A sequence's maps: frames planned together (MapPlanner) share one view and one colour range,
// and each frame written over that view covers only its own part of it.
#include "analyzer/maps/map_planner.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

namespace toonwater {
namespace {

TEST(SequenceMaps, FramesShareViewAndRange) {
  test::ScratchDir dir;
  // A quiet frame over [−1, 1]² and a loud one over [−1.5, 1.5]²: the view covers both.
  AnalyzeOptions options;
  options.flow.up = Axis::z;
  const Analysis quiet = analyze_mesh(make_wave_field(61, 0.03, 6.0, 1.0).mesh, options);
  const Analysis loud = analyze_mesh(make_wave_field(91, 0.1, 6.0, 1.5).mesh, options);
  MapPlanner planner(Axis::z);
  planner.add(quiet);
  planner.add(loud);
  const MapView view = planner.view(MapOptions{});
  const MapRanges ranges = planner.ranges();
  EXPECT_LE(view.box.u_min, -1.5);
  EXPECT_GE(view.box.u_max, 1.5);

  MapPlanner quiet_alone(Axis::z);
  quiet_alone.add(quiet);
  EXPECT_GT(ranges.mean, quiet_alone.ranges().mean);  // not the quiet frame's own range

  write_maps(dir / "maps", "water_0001", quiet, view, ranges);
  write_maps(dir / "maps", "water_0002", loud, view, ranges);
  for (const char* name : {"water_0001", "water_0002"}) {
    const test::ReadImage exr = test::read_image(dir / "maps" / (std::string(name) + ".exr"));
    const test::ReadImage png = test::read_image(dir / "maps" / (std::string(name) + "_K.png"));
    EXPECT_EQ(exr.spec.width, view.width) << name;
    EXPECT_EQ(exr.spec.height, view.height) << name;
    EXPECT_EQ(std::stod(exr.spec.get_string_attribute("toonwater:H_range")), ranges.mean);
    EXPECT_EQ(std::stod(png.spec.get_string_attribute("toonwater:K_range")), ranges.gaussian);
  }
  // The quiet frame covers only the middle of the shared view.
  const test::ReadImage first = test::read_image(dir / "maps" / "water_0001.exr");
  EXPECT_EQ(first.at(0, 0, "A"), 0.0f);
  EXPECT_EQ(first.at(view.width / 2, view.height / 2, "A"), 1.0f);
}

TEST(SequenceMaps, FrameStemDropsTheMeshExtensions) {
  EXPECT_EQ(frame_stem("sim/water_0001.obj"), "water_0001");
  EXPECT_EQ(frame_stem("cache/fluid_mesh_0001.bobj.gz"), "fluid_mesh_0001");
  EXPECT_EQ(frame_stem("water.v2_0003.ply"), "water.v2_0003");
}

}  // namespace
}  // namespace toonwater
