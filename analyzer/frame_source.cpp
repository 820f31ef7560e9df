// A sequence's frames, read and analysed once a pass (see frame_source.hpp).
#include "analyzer/frame_source.hpp"

#include "analyzer/mesh_reader.hpp"
#include "analyzer/stopwatch.hpp"

#include <chrono>

namespace toonwater {

SourceFrame FrameSource::read(const std::filesystem::path& path) {
  SourceFrame frame;
  frame.path = path;
  auto start = Clock::now();
  InputMesh input;
  ++reads_;
  try {
    input = read_mesh(path, options_.level_set);
  } catch (const EmptyMeshError& empty) {
    frame.empty = empty.what();
    frame.read_seconds = seconds_since(start);
    return frame;
  }
  if (options_.transform) apply_transform(*options_.transform, input.mesh, path);
  frame.read_seconds = seconds_since(start);
  if (options_.box) {
    frame.lower = frame.upper = input.mesh.positions.front();  // EmptyMeshError: at least one
    for (const Vec3& p : input.mesh.positions) {
      frame.lower = frame.lower.cwiseMin(p);
      frame.upper = frame.upper.cwiseMax(p);
    }
  }
  if (!options_.analysis) {
    frame.mesh = std::move(input.mesh);
    return frame;
  }
  start = Clock::now();
  AnalyzeOptions analysis = *options_.analysis;
  analysis.coherence = options_.coherent ? &coherence_ : nullptr;
  frame.analysis = analyze_mesh(std::move(input.mesh), analysis);
  frame.analysis_seconds = seconds_since(start);
  return frame;
}

}  // namespace toonwater
