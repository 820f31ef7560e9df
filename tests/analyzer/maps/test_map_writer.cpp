// Maps written to disk and read back with OpenImageIO: channels by name, analytic values,
// alpha, no NaN/Inf, preview colours at known points, metadata and shared sequence ranges.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/colormap.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "analyzer/maps/preview.hpp"
#include "tests/analyzer/maps/map_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace toonwater {
namespace {

namespace fs = std::filesystem;
using test::read_image;
using test::ReadImage;
using test::to_int;

double metadata(const ReadImage& image, const char* name) {
  const std::string text = image.spec.get_string_attribute(name);
  EXPECT_FALSE(text.empty()) << "no " << name;
  return text.empty() ? std::nan("") : std::stod(text);
}

TEST(MapWriter, WritesFourFilesAndNothingElse) {
  test::ScratchDir dir;
  const Analysis a = test::analyse(make_wave_field(41, 0.05).mesh, Axis::z);
  MapFiles files;
  write_frame_maps(dir.path(), "frame_0001", a, Axis::z, MapOptions{}, &files);
  EXPECT_EQ(files.exr, dir / "frame_0001.exr");
  EXPECT_EQ(files.gaussian_png, dir / "frame_0001_K.png");
  EXPECT_EQ(files.mean_png, dir / "frame_0001_H.png");
  EXPECT_EQ(files.label_png, dir / "frame_0001_label.png");
  std::size_t count = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    (void)entry;
    ++count;
  }
  EXPECT_EQ(count, 4u);  // no temporary files left behind
}

// Sphere cap and saddle through the files: K and H at the centre pixel within 2 % / 0.02.
TEST(MapWriter, ExrHoldsAnalyticCurvatureByChannelName) {
  test::ScratchDir dir;
  const Analysis sphere = test::analyse(make_icosphere(5, 2.0).mesh, Axis::z);
  write_frame_maps(dir.path(), "sphere", sphere, Axis::z, test::centred_options(2.0, 101));
  const ReadImage s = read_image(dir / "sphere.exr");
  ASSERT_EQ(s.spec.width, 101);
  EXPECT_EQ(s.spec.format, OIIO::TypeDesc::FLOAT);
  EXPECT_NEAR(s.at(50, 50, "K"), 0.25, 0.005);
  EXPECT_NEAR(s.at(50, 50, "H"), 0.5, 0.01);
  EXPECT_NEAR(s.at(50, 50, "height"), 2.0, 1e-3);
  EXPECT_EQ(s.at(50, 50, "A"), 1.0f);
  EXPECT_EQ(s.at(0, 0, "A"), 0.0f);  // outside the disk

  const Analysis saddle = test::analyse(make_saddle(81, 0.5).mesh, Axis::z);
  write_frame_maps(dir.path(), "saddle", saddle, Axis::z, test::centred_options(0.5, 81));
  const ReadImage d = read_image(dir / "saddle.exr");
  EXPECT_NEAR(d.at(40, 40, "K"), -1.0, 0.02);
  EXPECT_NEAR(d.at(40, 40, "H"), 0.0, 0.02);
  EXPECT_NEAR(d.at(40, 40, "k1"), 1.0, 0.02);
  EXPECT_NEAR(d.at(40, 40, "k2"), -1.0, 0.02);
}

TEST(MapWriter, NoNanOrInfAndAlphaZeroPixelsHoldZero) {
  test::ScratchDir dir;
  // A closed sphere mapped over a box larger than itself: a quarter of the map is outside.
  const Analysis a = test::analyse(make_icosphere(4, 1.0).mesh, Axis::z);
  MapOptions options = test::centred_options(1.5, 64);
  write_frame_maps(dir.path(), "m", a, Axis::z, options);
  const ReadImage m = read_image(dir / "m.exr");
  ASSERT_EQ(m.spec.nchannels, 7);
  const int alpha = m.channel("A");
  EXPECT_EQ(m.spec.alpha_channel, alpha);
  std::size_t outside = 0;
  for (int y = 0; y < m.spec.height; ++y)
    for (int x = 0; x < m.spec.width; ++x) {
      for (int c = 0; c < m.spec.nchannels; ++c) ASSERT_TRUE(std::isfinite(m.at(x, y, c)));
      if (m.at(x, y, alpha) != 0.0f) continue;
      ++outside;
      for (int c = 0; c < m.spec.nchannels; ++c) ASSERT_EQ(m.at(x, y, c), 0.0f);
    }
  EXPECT_GT(outside, 64u * 64u / 3);
}

TEST(MapWriter, MetadataCarriesRangesAndView) {
  test::ScratchDir dir;
  const Analysis a = test::analyse(make_wave_field(41, 0.05).mesh, Axis::z);
  const MapRanges ranges = write_frame_maps(dir.path(), "w", a, Axis::z, MapOptions{});
  EXPECT_GT(ranges.gaussian, 0.0);
  EXPECT_GT(ranges.mean, 0.0);
  for (const char* name : {"w.exr", "w_K.png", "w_H.png", "w_label.png"}) {
    const ReadImage image = read_image(dir / name);
    EXPECT_EQ(metadata(image, "toonwater:K_range"), ranges.gaussian) << name;
    EXPECT_EQ(metadata(image, "toonwater:H_range"), ranges.mean) << name;
    EXPECT_EQ(image.spec.get_string_attribute("toonwater:up"), "z") << name;
    EXPECT_EQ(image.spec.get_string_attribute("toonwater:columns"), "+x") << name;
    EXPECT_EQ(image.spec.get_string_attribute("toonwater:rows_down"), "-y") << name;
  }
}

// A flat plane is all zero: every map pixel has the diverging map's centre colour; the colour
// bar runs from the darkest blue to the darkest red; the title text is drawn in white.
TEST(MapWriter, PreviewColoursAtKnownPoints) {
  test::ScratchDir dir;
  const Analysis plane = test::analyse(make_wave_field(41, 0.0).mesh, Axis::z);
  write_frame_maps(dir.path(), "p", plane, Axis::z, test::centred_options(1.0, 50));
  const ReadImage k = read_image(dir / "p_K.png");
  ASSERT_EQ(k.spec.height, 50 + legend_height);
  ASSERT_EQ(k.spec.width, legend_min_width);
  EXPECT_EQ(k.rgb(25, 25), to_int(diverging_colour(0.0)));
  EXPECT_EQ(k.rgb(0, 0), to_int(diverging_colour(0.0)));
  EXPECT_EQ(k.rgb(200, 25), to_int(background_colour));  // right of the map
  const int bar_y = 50 + bar_top_offset + bar_rows / 2;
  EXPECT_EQ(k.rgb(bar_left, bar_y), to_int(diverging_colour(-1.0)));
  EXPECT_EQ(k.rgb(bar_right(k.spec.width), bar_y), to_int(diverging_colour(1.0)));
  EXPECT_EQ(k.rgb((bar_left + bar_right(k.spec.width)) / 2, bar_y), to_int(diverging_colour(0.0)));
  int white = 0;
  for (int y = 50; y < 50 + bar_top_offset; ++y)
    for (int x = 0; x < k.spec.width; ++x) white += k.rgb(x, y) == to_int(text_colour);
  EXPECT_GT(white, 20) << "no title text drawn";
}

// Every pixel of the previews has the colour of its EXR value; the label map shows ridges and
// valleys of a wave field in their colours.
TEST(MapWriter, PreviewColoursFollowTheMapValues) {
  test::ScratchDir dir;
  const Analysis wave = test::analyse(make_wave_field(81, 0.2, 6.0).mesh, Axis::z);
  const MapRanges r = write_frame_maps(dir.path(), "w", wave, Axis::z, MapOptions{});
  const ReadImage exr = read_image(dir / "w.exr");
  const ReadImage k = read_image(dir / "w_K.png"), h = read_image(dir / "w_H.png"),
                  label = read_image(dir / "w_label.png");
  int ridge = 0, valley = 0;
  for (int y = 0; y < exr.spec.height; y += 3)
    for (int x = 0; x < exr.spec.width; x += 3) {
      ASSERT_EQ(k.rgb(x, y), to_int(diverging_colour(exr.at(x, y, "K"), r.gaussian)));
      ASSERT_EQ(h.rgb(x, y), to_int(diverging_colour(exr.at(x, y, "H"), r.mean)));
      const int l = static_cast<int>(exr.at(x, y, "label"));
      ASSERT_EQ(label.rgb(x, y), to_int(label_colour(l)));
      ridge += l == 1;
      valley += l == -1;
    }
  EXPECT_GT(ridge, 0);
  EXPECT_GT(valley, 0);
  EXPECT_NE(label_colour(1), label_colour(0));
  EXPECT_NE(label_colour(-1), label_colour(0));
  EXPECT_NE(label_colour(1), label_colour(-1));
}

// Two frames, a quiet and a loud wave, share one range: both files carry it, and the quiet
// frame's crest is paler than the loud frame's at the same pixel (not renormalised away).
TEST(MapWriter, SharedRangeHoldsAcrossATwoFrameSequence) {
  test::ScratchDir dir;
  const TriangleMesh quiet = make_wave_field(81, 0.03).mesh, loud = make_wave_field(81, 0.1).mesh;
  MapPlanner planner(Axis::z);
  for (const TriangleMesh* frame : {&quiet, &loud}) planner.add(test::analyse(*frame, Axis::z));
  const MapView view = planner.view(MapOptions{});
  const MapRanges ranges = planner.ranges();
  write_maps(dir.path(), "f1", test::analyse(quiet, Axis::z), view, ranges);
  write_maps(dir.path(), "f2", test::analyse(loud, Axis::z), view, ranges);

  const ReadImage e1 = read_image(dir / "f1.exr"), e2 = read_image(dir / "f2.exr");
  const ReadImage p1 = read_image(dir / "f1_H.png"), p2 = read_image(dir / "f2_H.png");
  EXPECT_EQ(metadata(e1, "toonwater:H_range"), metadata(e2, "toonwater:H_range"));
  EXPECT_EQ(metadata(p1, "toonwater:K_range"), metadata(p2, "toonwater:K_range"));
  EXPECT_EQ(metadata(p1, "toonwater:H_range"), ranges.mean);
  ASSERT_EQ(e1.spec.width, e2.spec.width);

  // The loud frame's strongest crest pixel (largest H).
  int bx = 0, by = 0;
  for (int y = 0; y < e2.spec.height; ++y)
    for (int x = 0; x < e2.spec.width; ++x)
      if (e2.at(x, y, "H") > e2.at(bx, by, "H")) bx = x, by = y;
  ASSERT_GT(e1.at(bx, by, "H"), 0.0f);  // a crest in both frames
  // Red dominates more in the loud frame: green falls as the colour moves from white to red.
  EXPECT_LT(p2.rgb(bx, by)[1] + 40, p1.rgb(bx, by)[1]);
}

}  // namespace
}  // namespace toonwater
