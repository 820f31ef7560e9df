#include "analyzer/analysis.hpp"

#include "analyzer/curvature_jet.hpp"
#include "analyzer/curvature_smoothing.hpp"
#include "analyzer/stopwatch.hpp"
#include "analyzer/weld.hpp"

#include <chrono>

namespace toonwater {

Analysis analyze_mesh(TriangleMesh input, const AnalyzeOptions& options) {
  Analysis a;
  a.input_vertices = input.positions.size();

  auto start = Clock::now();
  WeldedMesh welded = weld_coincident_vertices(std::move(input));
  a.surface = std::move(welded.mesh);
  a.input_to_surface = std::move(welded.input_to_mesh);
  a.merged_vertices = welded.merged_vertex_count;
  a.times.weld = seconds_since(start);

  start = Clock::now();
  a.topology = analyze_topology(a.surface);
  a.flipped_faces = orient_consistently(a.surface, a.topology);
  a.times.topology = seconds_since(start);

  start = Clock::now();
  a.curvature = options.estimator == Estimator::jet ? compute_curvature_jet(a.surface, a.topology)
                                                    : compute_curvature(a.surface, a.topology);
  smooth_curvature(a.surface, a.topology.vertex_faces, a.curvature, options.smoothing_steps);
  a.times.curvature = seconds_since(start);

  start = Clock::now();
  if (options.flow_regions) {
    a.flow = find_flow_regions(a.surface, a.topology, a.curvature, options.flow, options.coherence);
  } else {
    a.flow.label.assign(a.surface.positions.size(), FlowLabel::none);
    a.flow.field.assign(a.surface.positions.size(), 0.0);
  }
  a.times.flow = seconds_since(start);
  return a;
}

}  // namespace toonwater
