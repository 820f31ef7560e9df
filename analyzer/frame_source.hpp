// One frame of a sequence from its file to its analysis, in the order the data flows:
//
//   read (mesh_reader.hpp) → to world coordinates (affine_transform.hpp) → empty-frame check →
//   analysis (analysis.hpp) → coherence with the frames before it (flow_coherence.hpp)
//
// The scene (povgen) and the curvature maps (analyzer/maps) take their frames from here: a pass
// over a sequence reads each frame once and analyses it once, with one set of options, and what
// the scene draws and what the maps show come from that one analysis. The frame's box is
// measured only when asked for (the default camera frames the sequence's box).
#pragma once

#include "analyzer/affine_transform.hpp"
#include "analyzer/analysis.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/mesh.hpp"
#include "analyzer/mesh_reader.hpp"

#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>

namespace toonwater {

struct FrameSourceOptions {
  std::optional<AffineTransform> transform;  // file to world coordinates; none: as read
  LevelSetOptions level_set;                 // .vdb frames: the grid and the mesher's adaptivity
  std::optional<AnalyzeOptions> analysis;    // none: read only (the options' coherence is unused)
  bool coherent = false;  // carry the flow state from frame to frame (flow_coherence.hpp)
  bool box = false;       // measure each frame's box (SourceFrame::lower, upper)
};

struct SourceFrame {
  std::filesystem::path path;
  std::string empty;  // why the frame holds no liquid (an empty mesh); "" when it has some
  Vec3 lower = Vec3::Zero(), upper = Vec3::Zero();  // box of its vertices (world), when asked
  TriangleMesh mesh;                 // world coordinates, when the source does not analyse
  std::optional<Analysis> analysis;  // when it does and the frame is not empty
  double read_seconds = 0, analysis_seconds = 0;
  bool has_water() const { return empty.empty(); }
};

// One pass over a sequence: frames are given in order (coherence carries state from each frame
// to the next). Throws InputError for a frame that cannot be read.
class FrameSource {
 public:
  explicit FrameSource(FrameSourceOptions options) : options_(std::move(options)) {}
  SourceFrame read(const std::filesystem::path& path);
  std::size_t reads() const { return reads_; }  // mesh files read
  bool analyses() const { return options_.analysis.has_value(); }

 private:
  FrameSourceOptions options_;
  FlowCoherence coherence_;
  std::size_t reads_ = 0;
};

}  // namespace toonwater
