// Maps of a frame sequence alone, with one shared view and one shared colour range
// (map_planner.hpp), in two passes over the files (frame_source.hpp) so that only one frame's
// analysis is in memory at a time: pass 1 reads and analyses every frame into a MapPlanner,
// pass 2 reads and analyses each frame again and writes its maps (map_writer.hpp) as STEM.exr,
// STEM_K.png, ... where STEM is the frame file's stem. (`toonwater povgen --maps` writes the
// maps from the scene's own two passes instead: povgen/povgen.hpp.)
#pragma once

#include "analyzer/affine_transform.hpp"
#include "analyzer/analysis.hpp"
#include "analyzer/maps/map_planner.hpp"

#include <cstddef>
#include <filesystem>
#include <string>
#include <functional>
#include <vector>

namespace toonwater {

struct SequenceMaps {
  MapView view;
  MapRanges ranges;
  std::size_t frames = 0;
};

// progress(done, total) is called after each frame. With `coherent_labels` the label maps show
// the flow regions made coherent from frame to frame (flow_coherence.hpp), as povgen renders
// them. A frame whose mesh is empty gets no maps. Throws InputError for a frame that cannot be
// read and OutputError for a map that cannot be written.
// `transform`, when given, maps each frame from file to world coordinates first.
SequenceMaps write_sequence_maps(const std::vector<std::filesystem::path>& frames,
                                 const AnalyzeOptions& analyze, const MapOptions& maps,
                                 const std::filesystem::path& dir, bool coherent_labels = true,
                                 const AffineTransform* transform = nullptr,
                                 const std::function<void(std::size_t, std::size_t)>& progress = {});

// The name a frame's maps take: the file name without its mesh extensions ("water_0001" for
// water_0001.obj, "fluid_mesh_0001" for fluid_mesh_0001.bobj.gz).
std::string frame_stem(const std::filesystem::path& frame);

}  // namespace toonwater
