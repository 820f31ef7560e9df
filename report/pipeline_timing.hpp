// The paper's Table 1 for toonwater: per input frame, its vertices, the flow
// analysis time (weld, topology, curvature, flow regions: analyze_mesh, with each estimator),
// the scene writing time (povgen) and POV-Ray's parse + trace time for the scene povgen wrote.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace toonwater::report {

struct PipelineInput {
  std::string name;
  std::filesystem::path mesh;  // one frame
  Axis up = Axis::y;
};

struct PipelineTiming {
  std::string name;
  std::size_t vertices = 0;
  double analysis_one_ring = 0;  // seconds, median of three runs
  double analysis_jet = 0;
  double scene_writing = 0;      // povgen's mesh2 and scene files
  std::optional<double> povray;  // parse + trace of one frame; empty when POV-Ray failed
  std::string povray_failure;
};

// Writes the scene into `work_dir` (created) and renders it at width × height.
PipelineTiming time_pipeline(const PipelineInput& input, const std::filesystem::path& work_dir,
                             int width, int height);

}  // namespace toonwater::report
