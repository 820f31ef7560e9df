// Two-pass maps of a sequence (see sequence_maps.hpp).
#include "analyzer/maps/sequence_maps.hpp"

#include "analyzer/flow_coherence.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "analyzer/mesh_reader.hpp"

#include <optional>

namespace toonwater {
namespace {

// The frame's analysis, or nothing for a frame whose mesh is empty (no liquid): it gets no map.
std::optional<Analysis> analyze_frame(const std::filesystem::path& frame,
                                      const AnalyzeOptions& analyze,
                                      const AffineTransform* transform) {
  try {
    InputMesh input = read_mesh(frame);
    if (transform) apply_transform(*transform, input.mesh);
    return analyze_mesh(std::move(input.mesh), analyze);
  } catch (const EmptyMeshError&) {
    return std::nullopt;
  }
}

}  // namespace

std::string frame_stem(const std::filesystem::path& frame) {
  std::filesystem::path stem = frame.stem();
  if (frame.extension() == ".gz") stem = stem.stem();
  return stem.string();
}

SequenceMaps write_sequence_maps(const std::vector<std::filesystem::path>& frames,
                                 const AnalyzeOptions& analyze, const MapOptions& maps,
                                 const std::filesystem::path& dir, bool coherent_labels,
                                 const AffineTransform* transform,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  MapPlanner planner(analyze.flow.up);
  for (const auto& frame : frames)
    if (std::optional<Analysis> a = analyze_frame(frame, analyze, transform)) planner.add(*a);
  SequenceMaps result;
  result.view = planner.view(maps);
  result.ranges = planner.ranges(maps.percentile);
  FlowCoherence coherence;
  AnalyzeOptions coherent = analyze;
  if (coherent_labels) coherent.coherence = &coherence;
  for (const auto& frame : frames) {
    if (std::optional<Analysis> a = analyze_frame(frame, coherent, transform)) {
      write_maps(dir, frame_stem(frame), *a, result.view, result.ranges);
      ++result.frames;
    }
    if (progress) progress(result.frames, frames.size());
  }
  return result;
}

}  // namespace toonwater
