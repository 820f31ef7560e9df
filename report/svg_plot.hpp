// A log–log line plot written as SVG text: decade grid and labels on both axes, one polyline
// with point markers per series, a legend on the right. Points with a non-positive or
// non-finite coordinate cannot be drawn on log axes and are left out.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace toonwater::report {

struct PlotSeries {
  std::string label;
  std::string color;                              // an SVG colour: "#1f77b4"
  std::string dashes;                             // an SVG stroke-dasharray ("" for a solid line)
  std::vector<std::pair<double, double>> points;  // (x, y), drawn in the given order
};

struct LogLogPlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<PlotSeries> series;
};

std::string render_svg(const LogLogPlot& plot);

}  // namespace toonwater::report
