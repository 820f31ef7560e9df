// `toonwater report`: runs the measurements below and writes, into one directory,
//   report.md              the report: tables, plots, and when each estimator is the better choice
//   curvature_errors.csv   every sample of the curvature study (curvature_study.hpp)
//   pipeline.csv           the Table 1 timings (pipeline_timing.hpp)
//   render_quality.csv     render presets against a reference render (render_error_study.hpp)
//   error_{K,H}_{regular,jittered,noisy}.svg, render_error.svg   error against run time, log–log
//   flow_ripples.csv, flow_mean.png, flow_paper.png   the flow criteria compared (flow_study.hpp)
// Every number in them comes from this run.
#pragma once

#include "report/curvature_study.hpp"
#include "report/flow_study.hpp"
#include "report/pipeline_timing.hpp"
#include "report/render_error_study.hpp"

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::report {

enum class ReportSize {
  quick,     // 1k–16k vertices, one run each, tiny renders: for CI
  standard,  // 1k–250k vertices, median of three runs, 640×480 renders
  full,      // standard plus 1M vertices
};

struct ReportOptions {
  std::filesystem::path out_dir;
  ReportSize size = ReportSize::standard;
  std::filesystem::path data_dir;  // holds mantaflow-wake/ and blender-ocean/; skipped if absent
  std::function<void(const std::string&)> progress;
};

struct ReportResult {
  std::vector<StudySample> study;
  std::vector<PipelineTiming> pipeline;
  std::optional<RenderQualityResult> render_quality;  // of the first pipeline input's scene
  std::string render_quality_failure;                 // why it is empty
  std::vector<RippleRow> ripples;                     // flow criteria on analytic ripples
  std::vector<SequenceFlowStudy> flow_sequence;       // and on mantaflow-wake from above
  std::string flow_sequence_failure;                  // why that is empty
};

ReportResult write_report(const ReportOptions& options);

}  // namespace toonwater::report
