// Calm water stays calm, and only what matters is drawn: a sequence seen from straight above,
// every band and region in a pure colour (opaque water, no outlines, no antialiasing), measured
// on the rendered pixels, frame by frame:
//   - the share of the water's pixels in flow regions, and of the flow pixels within 4 cells
//     of the tank's walls;
//   - the share of the water's pixels whose class (a band or a region) changed since the
//     previous frame;
//   - flow pieces of at least one cell² and band specks under one cell² (4-connected);
//   - the share of the water's pixels in the bright and dark bands together.
// A "cell" is the simulation's, given by the caller.
//
// The stroke study (issue #29) draws the same frames with `flow.style = "lines"`, strokes in
// pure red on flat grey water, and measures the strokes' steadiness: the share of a frame's
// stroke pixels with no stroke pixel within 2 px in the next frame (lost), and within one cell
// (gone: a stroke that moves with the water by up to a cell a frame is lost, not gone).
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/config.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::report {

struct OverheadOptions {
  Axis up = Axis::z;
  double cell = 0;          // the simulation's cell, scene units
  Vec3 tank_min, tank_max;  // input axes: the picture frames the box, its sides across up are walls
  std::vector<std::string> objects;  // mesh patterns, drawn in a colour of their own
  std::optional<FrameRange> frames;
  int width = 640, height = 400;
};

struct OverheadFrame {
  long frame = 0;
  std::size_t water_pixels = 0;
  std::size_t flow_pixels = 0, wall_flow_pixels = 0;
  double changed_share = 0;  // 0 for the first frame
  std::size_t flow_pieces = 0, band_specks = 0;
  double contrast_share = 0;
  double flow_share() const {
    return water_pixels ? static_cast<double>(flow_pixels) / static_cast<double>(water_pixels)
                        : 0.0;
  }
};

struct StrokeFrame {
  long frame = 0;
  std::size_t stroke_pixels = 0;
  std::size_t strokes = 0;        // drawn by the scene
  std::size_t stroke_pieces = 0;  // 8-connected pieces of stroke pixels
  double lost_share = 0;  // of stroke_pixels, none within 2 px in the next frame; 0 for the last
  double gone_share = 0;  // of stroke_pixels, none within a cell in the next frame; 0 for the last
};

// Scenes and frames go under `work_dir`. Throws std::runtime_error when a frame fails to render.
std::vector<OverheadFrame> run_overhead_study(const std::string& pattern,
                                              const OverheadOptions& options,
                                              const std::filesystem::path& work_dir);

// Scenes and frames go under `work_dir`. Throws std::runtime_error when a frame fails to render.
std::vector<StrokeFrame> run_stroke_study(const std::string& pattern,
                                          const OverheadOptions& options,
                                          const std::filesystem::path& work_dir);

}  // namespace toonwater::report
