// What every map of a frame or a sequence shares: the view (extent and pixel size) and the
// colour ranges of K and H. Frames are added one at a time and may then be dropped, so a
// sequence needs two passes over its frames but never holds more than one analysis:
//
//   MapPlanner planner(up);
//   for (frame : frames) planner.add(analyze(frame));             // pass 1
//   const MapView view = planner.view(options);
//   const MapRanges ranges = planner.ranges();
//   for (frame : frames) write_maps(dir, stem, analyze(frame), view, ranges);  // pass 2
//
// Extent: the union of the frames' mapped faces (n·up > 0, on the free surface: see
// top_down_map.hpp) seen from above, unless a box is given. Pixel size: the smallest median edge
// length of the frames over `pixels_per_edge`, unless a size is given; the longer side is capped at
// `max_size`. Ranges: CurvatureRanges (robust_range.hpp) over the mapped faces of all frames
// pooled, each vertex weighted by the area it covers in the map (a third of the projected area of
// its upward faces), i.e. the share of map pixels.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/maps/robust_range.hpp"
#include "analyzer/maps/top_down_map.hpp"

#include <optional>

namespace toonwater {

struct MapOptions {
  std::optional<MapBox> box;  // default: the upward-facing surface's extent
  std::optional<int> size;    // pixels along the longer side; default from the edge length
  double pixels_per_edge = 2.0;
  int max_size = 4096;
  double percentile = 0.98;  // of |value|, for the colour ranges
};

class MapPlanner {
 public:
  explicit MapPlanner(Axis up) : up_(up) {}
  void add(const Analysis& analysis);
  void add(const TriangleMesh& surface, const CurvatureField& curvature,
           std::span<const std::uint8_t> free_surface, double median_edge);
  std::size_t frames() const { return frames_; }
  // Throws std::runtime_error when there is nothing to map (no upward face and no box).
  MapView view(const MapOptions& options) const;
  MapRanges ranges(double percentile = MapOptions{}.percentile) const;

 private:
  Axis up_;
  std::size_t frames_ = 0;
  MapBox extent_{};
  bool has_extent_ = false;
  CurvatureRanges ranges_;
};

}  // namespace toonwater
