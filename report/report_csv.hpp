// The report's CSV files: every number behind its tables, one row per sample.
#pragma once

#include "report/curvature_study.hpp"
#include "report/flow_study.hpp"
#include "report/pipeline_timing.hpp"
#include "report/render_error_study.hpp"

#include <string>
#include <vector>

namespace toonwater::report {

std::string study_csv(const std::vector<StudySample>& samples);     // curvature_errors.csv
std::string pipeline_csv(const std::vector<PipelineTiming>& rows);  // pipeline.csv
std::string ripple_csv(const std::vector<RippleRow>& rows);         // flow_ripples.csv
std::string render_quality_csv(const RenderQualityResult& r);       // render_quality.csv

}  // namespace toonwater::report
