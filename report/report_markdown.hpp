// report.md: the tables, the plots' links and the conclusions, written from a run's results.
#pragma once

#include "report/report.hpp"

#include <filesystem>
#include <string>

namespace toonwater::report {

// What the text says about the run besides its results.
struct ReportRun {
  std::string size_name;         // "quick", "standard", "full"
  int repeats = 1;               // runs of the curvature stage per sample (the median is reported)
  std::string scene;             // the input whose scene the rendering error is measured on
  int width = 0, height = 0;     // of the renders
  double pixels_per_cell = 0.0;  // of the flow study's top-down renders
  std::filesystem::path data_dir;
};

std::string report_markdown(const ReportResult& result, const ReportRun& c);

}  // namespace toonwater::report
