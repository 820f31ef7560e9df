// Two-pass maps of a sequence (see sequence_maps.hpp).
#include "analyzer/maps/sequence_maps.hpp"

#include "analyzer/maps/map_writer.hpp"
#include "analyzer/mesh_reader.hpp"

namespace toonwater {

SequenceMaps write_sequence_maps(const std::vector<std::filesystem::path>& frames,
                                 const AnalyzeOptions& analyze, const MapOptions& maps,
                                 const std::filesystem::path& dir,
                                 const std::function<void(std::size_t, std::size_t)>& progress) {
  MapPlanner planner(analyze.flow.up);
  for (const auto& frame : frames) planner.add(analyze_mesh(read_mesh(frame).mesh, analyze));
  SequenceMaps result;
  result.view = planner.view(maps);
  result.ranges = planner.ranges(maps.percentile);
  for (const auto& frame : frames) {
    write_maps(dir, frame.stem().string(), analyze_mesh(read_mesh(frame).mesh, analyze),
               result.view, result.ranges);
    ++result.frames;
    if (progress) progress(result.frames, frames.size());
  }
  return result;
}

}  // namespace toonwater
