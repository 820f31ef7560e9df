// Two-pass maps of a sequence (see sequence_maps.hpp).
#include "analyzer/maps/sequence_maps.hpp"

#include "analyzer/frame_source.hpp"
#include "analyzer/maps/map_writer.hpp"

namespace toonwater {

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
  FrameSourceOptions plan_options;
  if (transform) plan_options.transform = *transform;
  plan_options.analysis = analyze;
  FrameSourceOptions write_options = plan_options;
  write_options.coherent = coherent_labels;

  MapPlanner planner(analyze.flow.up);
  FrameSource plan_pass(plan_options);
  for (const auto& frame : frames)
    if (SourceFrame f = plan_pass.read(frame); f.has_water()) planner.add(*f.analysis);
  SequenceMaps result;
  result.view = planner.view(maps);
  result.ranges = planner.ranges(maps.percentile);
  FrameSource write_pass(write_options);
  for (const auto& frame : frames) {
    if (SourceFrame f = write_pass.read(frame); f.has_water()) {
      write_maps(dir, frame_stem(frame), *f.analysis, result.view, result.ranges);
      ++result.frames;
    }
    if (progress) progress(result.frames, frames.size());
  }
  return result;
}

}  // namespace toonwater
