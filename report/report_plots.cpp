#include "report/report_plots.hpp"

#include "report/sample_analysis.hpp"
#include "report/svg_plot.hpp"

#include <map>

namespace toonwater::report {
namespace {

const std::map<std::string, std::string> method_colors = {{"one-ring", "#d62728"},
                                                          {"one-ring+smooth2", "#ff9896"},
                                                          {"jet", "#1f77b4"},
                                                          {"jet+smooth2", "#9edae5"}};
const std::map<std::string, std::string> surface_dashes = {
    {"sphere", ""},       {"uv sphere", "4,2,1,2"}, {"torus", "6,3"},
    {"ellipsoid", "2,2"}, {"saddle", "8,3,2,3"},    {"height field", "1,4"}};

}  // namespace

std::string error_plot_name(const std::string& sampling, bool mean) {
  return std::string("error_") + (mean ? "H" : "K") + "_" + sampling + ".svg";
}

std::string error_plot(const std::vector<StudySample>& samples, const std::string& sampling,
                       bool mean) {
  LogLogPlot plot;
  plot.title = std::string(mean ? "H" : "K") + " error against run time, " + sampling + " meshes";
  plot.x_label = "median run time of the curvature stage (s)";
  plot.y_label = std::string("RMS error of ") + (mean ? "H" : "K") + " / RMS of the exact value";
  for (const Method& method : study_methods()) {
    for (const std::string& surface : study_surfaces) {
      PlotSeries series{method.name + ", " + surface,
                        method_colors.at(method.name),
                        surface_dashes.at(surface),
                        {}};
      for (std::size_t n : resolutions(samples, surface))
        if (const StudySample* s = find(samples, surface, sampling, method.name, n))
          series.points.emplace_back(s->seconds, mean ? s->rms_mean : s->rms_gaussian);
      plot.series.push_back(std::move(series));
    }
  }
  return render_svg(plot);
}

std::string render_quality_plot(const RenderQualityResult& r) {
  LogLogPlot plot{"Rendering error against POV-Ray time",
                  "POV-Ray parse + trace (s)",
                  "error against the reference render",
                  {}};
  PlotSeries rmse{"RMSE (RGB in [0, 1])", "#1f77b4", "", {}};
  PlotSeries bands{"share of pixels in another band", "#d62728", "6,3", {}};
  for (const RenderQualitySample& p : r.presets) {
    rmse.points.emplace_back(p.seconds, p.rmse);
    bands.points.emplace_back(p.seconds, p.band_mismatch);
  }
  plot.series = {rmse, bands};
  return render_svg(plot);
}

}  // namespace toonwater::report
