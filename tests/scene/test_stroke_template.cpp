// Toon_stroke (templates/toon.inc) rendered by POV-Ray without antialiasing, as a preview or a
// pure-colour measurement renders it: a tapered stroke, and a fading one, is one unbroken piece
// of pixels whose ends are narrower than its middle. No part is drawn under a pixel wide, since
// it would break into specks.
#include "report/image.hpp"
#include "scene/toon_template.hpp"
#include "tests/support/povray_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

constexpr int kImage = 200;
constexpr int kPoints = 61;
constexpr int kTaperPoints = 15;  // the taper rises over this many points from each end

// The stroke's pixels (pure red on grey) for a line from (−4, 0, −2.5) to (4, 0, 2.5) seen
// from 10 above, `width` pixels wide, its taper times `strength`.
std::vector<std::uint8_t> render_stroke(const std::filesystem::path& dir, double width,
                                        double strength) {
  std::string points, taper;
  for (int i = 0; i < kPoints; ++i) {
    const double s = static_cast<double>(i) / (kPoints - 1);
    const double t = std::min(1.0, std::min(i, kPoints - 1 - i) / double{kTaperPoints});
    const char* separator = i ? "," : "";
    points.append(separator).append("<").append(std::to_string(-4 + 8 * s)).append(",0,");
    points.append(std::to_string(-2.5 + 5 * s)).append(">");
    taper.append(separator).append(std::to_string(strength * t));
  }
  write_text(dir / "toon.inc", std::string(toon_template()));
  write_text(dir / "scene.pov",
             "#version 3.7;\n#include \"toon.inc\"\n"
             "global_settings { assumed_gamma 1.0 }\n"
             "#declare Toon_line_width = " +
                 std::to_string(width) +
                 ";\n#declare Toon_camera_location = <0, 10, 0>;\n"
                 "#declare Toon_pixel_angle = 2 * tan(radians(40) / 2) / image_width;\n"
                 "camera { location Toon_camera_location look_at <0, 0, 0> sky z angle 40 }\n"
                 "background { color srgb 0.5 }\n"
                 "object { union { Toon_stroke(array[" +
                 std::to_string(kPoints) + "] {" + points + "}, array[" + std::to_string(kPoints) +
                 "] {" + taper +
                 "}, 0) }\n"
                 "  texture { pigment { color rgb <1, 0, 0> } finish { emission 1 diffuse 0 "
                 "ambient 0 } } }\n");
  write_text(dir / "scene.ini",
             "Input_File_Name=scene.pov\nOutput_File_Name=frame.png\n"
             "Output_File_Type=N\nWidth=" +
                 std::to_string(kImage) + "\nHeight=" + std::to_string(kImage) +
                 "\nAntialias=Off\nDisplay=Off\n");
  const Povray p = run_povray(dir);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  if (p.exit_code != 0) return {};
  const Image img = read_image(dir / "frame.png");
  EXPECT_EQ(img.width, kImage);
  EXPECT_EQ(img.height, kImage);
  if (img.width != kImage || img.height != kImage) return {};
  return mask_of(img, Rgb8{255, 0, 0});
}

// The stroke's pixels in each column it crosses, from one end to the other.
std::vector<int> column_counts(const std::vector<std::uint8_t>& red) {
  std::vector<int> counts;
  for (int x = 0; x < kImage; ++x) {
    int count = 0;
    for (int y = 0; y < kImage; ++y) count += red[static_cast<std::size_t>(y) * kImage + x];
    if (count > 0 || !counts.empty()) counts.push_back(count);
  }
  while (!counts.empty() && counts.back() == 0) counts.pop_back();
  return counts;
}

int median(std::vector<int> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The counts of the stroke's middle third, away from its tapered ends.
std::vector<int> middle_third(const std::vector<int>& columns) {
  const std::size_t n = columns.size();
  return {columns.begin() + static_cast<long>(n / 3),
          columns.begin() + static_cast<long>(2 * n / 3)};
}

TEST(StrokeTemplate, ATaperedStrokeIsOnePieceNarrowerAtItsEnds) {
  for (const double width : {2.0, 3.0, 5.0}) {
    SCOPED_TRACE(width);
    ScratchDir dir;
    const std::vector<std::uint8_t> red = render_stroke(dir.path(), width, 1.0);
    ASSERT_FALSE(red.empty());
    EXPECT_EQ(report::pieces_of(red, kImage), 1u) << "specks beside the stroke's ends";
    const std::vector<int> columns = column_counts(red);
    ASSERT_GT(columns.size(), static_cast<std::size_t>(kImage / 2)) << "no stroke across";
    EXPECT_EQ(std::count(columns.begin(), columns.end(), 0), 0) << "a gap in the stroke";
    // The taper's first half at each end against the stroke's middle third.
    const std::size_t n = columns.size(), tip = n * kTaperPoints / (2 * (kPoints - 1));
    const std::vector<int> ends{columns.begin(), columns.begin() + static_cast<long>(tip)};
    const std::vector<int> middle = middle_third(columns);
    EXPECT_LT(median(ends), median(middle)) << "the stroke does not taper";
    EXPECT_LT(*std::max_element(ends.begin(), ends.end()),
              *std::max_element(middle.begin(), middle.end()));
  }
}

// A stroke fading in or out (its taper times a strength under 1) is drawn narrower, but never
// under a pixel wide: thinner, it would break into dots where there is no antialiasing.
TEST(StrokeTemplate, AFadingStrokeIsNarrowerButStillOnePiece) {
  for (const double width : {2.0, 3.0}) {
    SCOPED_TRACE(width);
    ScratchDir full_dir, fading_dir;
    const std::vector<std::uint8_t> full = render_stroke(full_dir.path(), width, 1.0);
    const std::vector<std::uint8_t> fading = render_stroke(fading_dir.path(), width, 1.0 / 3.0);
    ASSERT_FALSE(full.empty());
    ASSERT_FALSE(fading.empty());
    EXPECT_EQ(report::pieces_of(fading, kImage), 1u) << "a fading stroke broken into dots";
    const std::vector<int> full_columns = column_counts(full);
    const std::vector<int> columns = column_counts(fading);
    ASSERT_GT(columns.size(), static_cast<std::size_t>(kImage / 2)) << "no stroke across";
    EXPECT_EQ(std::count(columns.begin(), columns.end(), 0), 0) << "a gap in the stroke";
    EXPECT_LT(median(middle_third(columns)), median(middle_third(full_columns))) << "not narrower";
  }
}

}  // namespace
}  // namespace toonwater::test
