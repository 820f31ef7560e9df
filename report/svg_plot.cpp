// SVG log–log plot; see svg_plot.hpp. Labels and titles are escaped for XML.
#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace toonwater::report {
namespace {

constexpr double width = 900, height = 520;
constexpr double left = 80, right = 640, top = 40, bottom = 460;  // the plotting area

std::string escaped(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.1f", value);
  return buffer;
}

bool drawable(const std::pair<double, double>& p) {
  return std::isfinite(p.first) && std::isfinite(p.second) && p.first > 0 && p.second > 0;
}

// Whole decades enclosing [lo, hi] (log10 values).
std::pair<int, int> decades(double lo, double hi) {
  int first = static_cast<int>(std::floor(lo)), last = static_cast<int>(std::ceil(hi));
  if (last == first) ++last;
  return {first, last};
}

}  // namespace

std::string render_svg(const LogLogPlot& plot) {
  double x_lo = std::numeric_limits<double>::max(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const PlotSeries& s : plot.series)
    for (const auto& p : s.points)
      if (drawable(p)) {
        x_lo = std::min(x_lo, std::log10(p.first));
        x_hi = std::max(x_hi, std::log10(p.first));
        y_lo = std::min(y_lo, std::log10(p.second));
        y_hi = std::max(y_hi, std::log10(p.second));
      }
  if (x_lo > x_hi) x_lo = x_hi = y_lo = y_hi = 0.0;  // nothing drawable: an empty decade
  // Named pairs rather than structured bindings: Clang before 16 cannot capture those in lambdas.
  const std::pair<int, int> x_decades = decades(x_lo, x_hi);
  const std::pair<int, int> y_decades = decades(y_lo, y_hi);
  const int x_first = x_decades.first, x_last = x_decades.second;
  const int y_first = y_decades.first, y_last = y_decades.second;
  auto sx = [&](double x) {
    return left + (std::log10(x) - x_first) / (x_last - x_first) * (right - left);
  };
  auto sy = [&](double y) {
    return bottom - (std::log10(y) - y_first) / (y_last - y_first) * (bottom - top);
  };

  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + number(width) +
                    "\" height=\"" + number(height) +
                    "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg += "<text x=\"" + number((left + right) / 2) +
         "\" y=\"22\" text-anchor=\"middle\" font-size=\"15\">" + escaped(plot.title) + "</text>\n";
  for (int d = x_first; d <= x_last; ++d) {
    const double x = left + double(d - x_first) / (x_last - x_first) * (right - left);
    svg += "<line x1=\"" + number(x) + "\" y1=\"" + number(top) + "\" x2=\"" + number(x) +
           "\" y2=\"" + number(bottom) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + number(x) + "\" y=\"" + number(bottom + 18) +
           "\" text-anchor=\"middle\">1e" + std::to_string(d) + "</text>\n";
  }
  for (int d = y_first; d <= y_last; ++d) {
    const double y = bottom - double(d - y_first) / (y_last - y_first) * (bottom - top);
    svg += "<line x1=\"" + number(left) + "\" y1=\"" + number(y) + "\" x2=\"" + number(right) +
           "\" y2=\"" + number(y) + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + number(left - 6) + "\" y=\"" + number(y + 4) +
           "\" text-anchor=\"end\">1e" + std::to_string(d) + "</text>\n";
  }
  svg += "<rect x=\"" + number(left) + "\" y=\"" + number(top) + "\" width=\"" +
         number(right - left) + "\" height=\"" + number(bottom - top) +
         "\" fill=\"none\" stroke=\"black\"/>\n";
  svg += "<text x=\"" + number((left + right) / 2) + "\" y=\"" + number(bottom + 40) +
         "\" text-anchor=\"middle\">" + escaped(plot.x_label) + "</text>\n";
  svg += "<text transform=\"translate(22," + number((top + bottom) / 2) +
         ") rotate(-90)\" text-anchor=\"middle\">" + escaped(plot.y_label) + "</text>\n";

  double legend_y = top + 6;
  for (const PlotSeries& s : plot.series) {
    const std::string dash = s.dashes.empty() ? "" : " stroke-dasharray=\"" + s.dashes + "\"";
    std::string points;
    for (const auto& p : s.points)
      if (drawable(p)) points += number(sx(p.first)) + "," + number(sy(p.second)) + " ";
    svg += "<polyline fill=\"none\" stroke=\"" + s.color + "\" stroke-width=\"1.6\"" + dash +
           " points=\"" + points + "\"/>\n";
    for (const auto& p : s.points)
      if (drawable(p))
        svg += "<circle cx=\"" + number(sx(p.first)) + "\" cy=\"" + number(sy(p.second)) +
               "\" r=\"2.5\" fill=\"" + s.color + "\"/>\n";
    svg += "<line x1=\"" + number(right + 16) + "\" y1=\"" + number(legend_y) + "\" x2=\"" +
           number(right + 46) + "\" y2=\"" + number(legend_y) + "\" stroke=\"" + s.color +
           "\" stroke-width=\"1.6\"" + dash + "/>\n";
    svg += "<text x=\"" + number(right + 52) + "\" y=\"" + number(legend_y + 4) + "\">" +
           escaped(s.label) + "</text>\n";
    legend_y += 16;
  }
  svg += "</svg>\n";
  return svg;
}

}  // namespace toonwater::report
