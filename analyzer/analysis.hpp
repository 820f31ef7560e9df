// The analyzer's pipeline on one mesh: weld, orient, topology, curvature, flow regions.
// Results are per welded vertex; `input_to_surface` maps every input vertex to its row.
#pragma once

#include "analyzer/curvature.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace toonwater {

// Curvature estimators: the paper's one-ring operators (curvature.hpp), or jets fitted over the
// two-ring (curvature_jet.hpp): slower, but accurate on irregular and noisy meshes.
enum class Estimator : std::uint8_t { one_ring, jet };

struct AnalyzeOptions {
  FlowOptions flow;
  bool flow_regions = true;  // false: curvature only, all labels 0
  Estimator estimator = Estimator::one_ring;
  int smoothing_steps = 0;             // curvature_smoothing.hpp; 0: none
  FlowCoherence* coherence = nullptr;  // a sequence's carried flow state (flow_coherence.hpp)
};

struct StageTimes {  // seconds
  double weld = 0, topology = 0, curvature = 0, flow = 0;
};

struct Analysis {
  TriangleMesh surface;  // welded, consistently oriented
  std::vector<std::int32_t> input_to_surface;
  MeshTopology topology;
  CurvatureField curvature;
  FlowRegions flow;
  std::size_t input_vertices = 0;
  std::size_t merged_vertices = 0;  // welded into another input vertex
  std::size_t flipped_faces = 0;
  StageTimes times;
};

// Takes the mesh by value: pass it with std::move when it is not needed afterwards.
Analysis analyze_mesh(TriangleMesh input, const AnalyzeOptions& options);

}  // namespace toonwater
