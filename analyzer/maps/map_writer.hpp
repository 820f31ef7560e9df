// Writes the curvature maps of one frame into a directory:
//   STEM.exr        float OpenEXR, channels height, K, H, k1, k2, label, A (alpha), ZIP-free
//                   fast compression (see map_writer.cpp); EXR sorts channels by name, so read
//                   them by name
//   STEM_K.png      Gaussian curvature preview (diverging colours over ±range)
//   STEM_H.png      mean curvature preview
//   STEM_label.png  flow labels: valley, none, ridge
// Metadata in every file: toonwater:K_range, toonwater:H_range (the colour ranges), the up
// axis and the map's box and pixel size. Each file is encoded in memory and written atomically
// (atomic_file.hpp): a failure leaves no partial file and keeps an older file intact.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/maps/map_planner.hpp"
#include "analyzer/maps/top_down_map.hpp"

#include <filesystem>
#include <string>

namespace toonwater {

struct MapFiles {
  std::filesystem::path exr, gaussian_png, mean_png, label_png;
};

// The four files' names for a frame's `stem` in `dir`.
MapFiles map_files(const std::filesystem::path& dir, const std::string& stem);

// Rasterises `analysis.surface` over `view` and writes the four files. Creates `dir`.
MapFiles write_maps(const std::filesystem::path& dir, const std::string& stem,
                    const Analysis& analysis, const MapView& view, const MapRanges& ranges);
MapFiles write_maps(const std::filesystem::path& dir, const std::string& stem,
                    const TopDownMap& map, const MapRanges& ranges);

// The name a frame's maps take: the file name without its mesh extensions ("water_0001" for
// water_0001.obj, "fluid_mesh_0001" for fluid_mesh_0001.bobj.gz).
std::string frame_stem(const std::filesystem::path& frame);

// The single-frame case: plan from this analysis alone, then write. Returns the ranges used.
// A sequence's maps share one view and one range: plan them over every frame (MapPlanner), then
// write each frame with write_maps, as `povgen --maps` does.
MapRanges write_frame_maps(const std::filesystem::path& dir, const std::string& stem,
                           const Analysis& analysis, Axis up, const MapOptions& options,
                           MapFiles* files = nullptr);

}  // namespace toonwater
