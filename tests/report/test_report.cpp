// toonwater report: the reduced run CI makes (--quick), read back from its CSV files, and the
// SVG plot writer. The quick run renders with POV-Ray at 160×120.
#include "report/svg_plot.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

using Row = std::vector<std::string>;

std::vector<Row> read_csv(const std::string& text) {
  std::vector<Row> rows;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    Row row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) row.push_back(field);
    if (!line.empty() && line.back() == ',') row.emplace_back();
    rows.push_back(row);
  }
  return rows;
}

double number(const std::string& text) {
  std::size_t used = 0;
  const double value = std::stod(text, &used);
  EXPECT_EQ(used, text.size()) << text;
  return value;
}

TEST(Report, QuickRunHasFiniteNumbersAndErrorsFallingOnRegularMeshes) {
  ScratchDir dir;
  const std::filesystem::path data = shared_dir().empty() ? dir.path() : shared_dir() / "data";
  // A user's own DIR/work is no concern of the report's: it stays as it was.
  std::filesystem::create_directories(dir / "out" / "work");
  write_text(dir / "out" / "work" / "mine.txt", "mine");
  const CommandResult r = run_toonwater(
      {"report", "--quick", "--out", (dir / "out").string(), "--data", data.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(dir / "out" / "work" / "mine.txt"), "mine");
  for (const auto& entry : std::filesystem::directory_iterator(dir / "out"))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
        << entry.path() << ": the work directory is left behind";

  const std::vector<Row> study = read_csv(read_text(dir / "out" / "curvature_errors.csv"));
  ASSERT_EQ(study.front(), (Row{"surface", "sampling", "method", "vertices", "rms_K", "max_K",
                                "rms_H", "max_H", "median_seconds"}));
  // 6 surfaces × 3 samplings × 3 resolutions × 4 methods.
  ASSERT_EQ(study.size(), 1u + 6 * 3 * 3 * 4);
  std::map<std::string, std::vector<std::pair<double, std::pair<double, double>>>> regular;
  for (std::size_t i = 1; i < study.size(); ++i) {
    const Row& row = study[i];
    ASSERT_EQ(row.size(), 9u);
    for (std::size_t c = 3; c < 9; ++c) {
      const double value = number(row[c]);
      EXPECT_TRUE(std::isfinite(value) && value > 0.0) << row[0] << " " << row[2] << " " << c;
    }
    EXPECT_LE(number(row[4]), number(row[5]));  // RMS ≤ max
    EXPECT_LE(number(row[6]), number(row[7]));
    if (row[1] == "regular")
      regular[row[0] + ", " + row[2]].push_back({number(row[3]), {number(row[4]), number(row[6])}});
  }
  ASSERT_EQ(regular.size(), 24u);
  for (const auto& [series, points] : regular) {
    SCOPED_TRACE(series);
    ASSERT_EQ(points.size(), 3u);
    for (std::size_t i = 1; i < points.size(); ++i) {
      EXPECT_GT(points[i].first, points[i - 1].first);
      EXPECT_LT(points[i].second.first, points[i - 1].second.first);    // K
      EXPECT_LT(points[i].second.second, points[i - 1].second.second);  // H
    }
  }

  const std::vector<Row> pipeline = read_csv(read_text(dir / "out" / "pipeline.csv"));
  ASSERT_GE(pipeline.size(), 2u);
  EXPECT_EQ(pipeline[1][0], "generated height field");
  EXPECT_EQ(number(pipeline[1][1]), 101.0 * 101.0);
  for (std::size_t c = 2; c < 7; ++c) {
    ASSERT_FALSE(pipeline[1][c].empty()) << "column " << c << " not measured";
    const double seconds = number(pipeline[1][c]);
    EXPECT_TRUE(std::isfinite(seconds) && seconds > 0.0) << c;
  }

  // Render presets against the reference render: finite, and the final preset closer to the
  // reference than the half-size, unantialiased draft.
  const std::vector<Row> quality = read_csv(read_text(dir / "out" / "render_quality.csv"));
  ASSERT_EQ(quality.size(), 4u);
  EXPECT_EQ(quality[1][0], "draft");
  EXPECT_EQ(quality[3][0], "final");
  for (std::size_t i = 1; i < quality.size(); ++i) {
    for (std::size_t c = 1; c < 6; ++c) EXPECT_TRUE(std::isfinite(number(quality[i][c]))) << i << c;
    EXPECT_GE(number(quality[i][1]), 80.0) << i;  // width: half of 160 at the least
    EXPECT_GE(number(quality[i][2]), 60.0) << i;
    EXPECT_GT(number(quality[i][3]), 0.0) << i;  // seconds
    EXPECT_GE(number(quality[i][4]), 0.0) << i;  // RMSE of RGB in [0, 1]
    EXPECT_LE(number(quality[i][4]), 1.0) << i;
    EXPECT_GE(number(quality[i][5]), 0.0) << i;  // a share of the pixels
    EXPECT_LE(number(quality[i][5]), 1.0) << i;
  }
  EXPECT_EQ(number(quality[1][1]) * 2, number(quality[3][1]));
  EXPECT_LT(number(quality[3][4]), number(quality[1][4]));  // RMSE
  EXPECT_LT(number(quality[3][5]), number(quality[1][5]));  // pixels in another band
  EXPECT_GT(number(quality[1][4]), 0.0);

  const std::string md = read_text(dir / "out" / "report.md");
  for (const char* part : {"## 1.", "## 2.", "## 3.", "## 4.", "## 5.", "error_H_jittered.svg"})
    EXPECT_NE(md.find(part), std::string::npos) << part;
  // The flow criteria on ripples: the default draws the crest circles, the paper's rule less.
  const std::vector<Row> ripples = read_csv(read_text(dir / "out" / "flow_ripples.csv"));
  ASSERT_EQ(ripples.front(), (Row{"criterion", "n", "jittered", "crest_ridge", "trough_valley",
                                  "calm_labelled", "labelled_share"}));
  ASSERT_EQ(ripples.size(), 1u + 2 * 2 * 2);  // criteria × meshes × resolutions
  for (std::size_t i = 1; i < ripples.size(); ++i) {
    const double crest = number(ripples[i][3]);
    EXPECT_TRUE(ripples[i][0] == "mean" ? crest >= 0.8 : crest < 0.5)
        << ripples[i][0] << " " << crest;
  }
  if (!shared_dir().empty()) {
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "flow_mean.png"));
    EXPECT_TRUE(std::filesystem::is_regular_file(dir / "out" / "flow_paper.png"));
  }
  const std::string svg = read_text(dir / "out" / "error_H_jittered.svg");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_GE(std::count(svg.begin(), svg.end(), '\n'), 20);
}

TEST(Report, APartThatFailsIsReportedAsNotMeasuredAndTheExitCodeSaysSo) {
  ScratchDir dir;
  const std::filesystem::path out = dir / "out", data = dir / "data";
  // Sample data that is there but broken: the flow study fails, the rest is measured.
  std::filesystem::create_directories(data / "mantaflow-wake");
  for (int frame = 1; frame <= 15; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "water_%04d.obj", frame);
    write_text(data / "mantaflow-wake" / name, "v 0 0 nan\nf 1 1 1\n");
  }
  const CommandResult r =
      run_toonwater({"report", "--quick", "--out", out.string(), "--data", data.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("water_0010.obj"), std::string::npos) << r.output;
  const std::string report = read_text(out / "report.md");
  EXPECT_NE(report.find("Not measured: "), std::string::npos);
  EXPECT_NE(report.find("water_0010.obj"), std::string::npos) << "the report says why";
  EXPECT_TRUE(std::filesystem::exists(out / "curvature_errors.csv")) << "the rest is written";
  for (const auto& entry : std::filesystem::directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
}

TEST(SvgPlot, PlacesPointsOnLogAxesAndEscapesText) {
  report::LogLogPlot plot{"a <title> & more", "x", "y", {}};
  plot.series.push_back({"s\"1\"", "#000000", "", {{1e-3, 1e-2}, {1e-1, 1.0}, {0.0, 5.0}}});
  const std::string svg = report::render_svg(plot);
  EXPECT_NE(svg.find("a &lt;title&gt; &amp; more"), std::string::npos);
  EXPECT_NE(svg.find("s&quot;1&quot;"), std::string::npos);
  // Decades 1e-3..1e-1 on x span the plotting area [80, 640], 1e-2..1e0 on y span [460, 40]:
  // the two drawable points are its corners; the point at x = 0 is left out.
  EXPECT_NE(svg.find("points=\"80.0,460.0 640.0,40.0 \""), std::string::npos) << svg;
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

}  // namespace
}  // namespace toonwater::test
