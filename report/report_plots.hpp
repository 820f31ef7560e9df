// The report's log–log plots (SVG, report/svg_plot.hpp): curvature error against run time per
// sampling, and rendering error against POV-Ray time.
#pragma once

#include "report/curvature_study.hpp"
#include "report/render_error_study.hpp"

#include <string>
#include <vector>

namespace toonwater::report {

// error_{H,K}_SAMPLING.svg: every method on every surface.
std::string error_plot_name(const std::string& sampling, bool mean);
std::string error_plot(const std::vector<StudySample>& samples, const std::string& sampling,
                       bool mean);

// render_error.svg: RMSE and band mismatch of each preset against its time.
std::string render_quality_plot(const RenderQualityResult& r);

}  // namespace toonwater::report
