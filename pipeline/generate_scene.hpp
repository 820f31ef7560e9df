// povgen: simulation frames in, a POV-Ray scene directory out.
//
//   DIR/scene.pov            the same for every frame (scene/scene_writer.hpp)
//   DIR/scene.ini            frame range, size, output names
//   DIR/toon.inc             the parts of the shading template it uses (templates/toon.inc)
//   DIR/water_NNNN.inc       per frame: Water_mesh (+ Water_shell) as mesh2
//   DIR/obj_NAME[.NNNN].inc  per object (per frame if animated): Obj_NAME_mesh (+ _shell)
//   DIR/spray_NNNN.inc       per frame, with particles: Spray_droplets (droplet_writer.hpp)
//   DIR/foam_NNNN.inc        per frame, with particles: Foam_patches (foam_writer.hpp)
//   DIR/bubbles_NNNN.inc     per frame, with particles: Water_bubbles (bubble_writer.hpp)
//
// All references inside are relative, so DIR can be moved. The directory is replaced whole, or
// not at all (scene_directory.hpp).
#pragma once

#include "analyzer/affine_transform.hpp"
#include "analyzer/analysis.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/stroke_persistence.hpp"
#include "analyzer/flow_strokes.hpp"
#include "analyzer/maps/map_planner.hpp"
#include "pipeline/frame_result.hpp"
#include "scene/config.hpp"
#include "scene/prepared_surface.hpp"

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace toonwater {

// The one mapping from the scene's configuration to the analysis of its water frames:
// `scene_flow` is the flow settings the scene is drawn with, null when it needs the geometry
// only (toon bands from the mesh's own normals, no flow regions or lines); `water_analysis` the
// options a water frame is analysed with, nothing for the geometry only. The toon bands'
// smoothed shading normals and their noise floor come from the flow stage whether or not flow
// regions are drawn; a curvature view needs the curvature. Curvature maps (`maps`) need the flow
// regions (their labels and free surface) whatever the scene draws. `analysis_options` is the
// part both share: the flow settings, with flow regions for the toon shading only.
const FlowConfig* scene_flow(const SceneConfig& config);
std::optional<AnalyzeOptions> water_analysis(const SceneConfig& config, Axis up, bool maps);
AnalyzeOptions analysis_options(const FlowConfig& flow, Axis up, WaterShading shading);

// The scene's surface from a mesh, analysed here (prepare_surface in prepared_surface.hpp):
// with `coherence`, the field is made coherent with the frames it saw before (a sequence's
// frames in order).
PreparedSurface prepare_surface(TriangleMesh input, Axis up, const FlowConfig* flow,
                                FlowCoherence* coherence, WaterShading shading = WaterShading::toon,
                                WaterNormals normals = WaterNormals::smoothed);

struct PovgenRequest {
  std::string water_pattern;
  std::optional<AffineTransform> water_transform;  // file to world coordinates of the water
  LevelSetOptions water_level_set;                 // .vdb water: the grid and the adaptivity
  // Secondary particle caches (analyzer/particles.hpp), each a file or a sequence with a file
  // for every water frame, placed by water_transform like the water.
  std::vector<std::string> particle_patterns;
  std::filesystem::path base_dir;  // patterns on the command line are relative to it
  Axis up = Axis::y;
  std::filesystem::path out_dir;
  bool force = false;  // write into a non-empty directory that is not a toonwater scene
  // Also the curvature maps of the water frames (analyzer/maps: STEM.exr, STEM_K.png, ...) into
  // this directory, from the scene's own reads and analyses of its frames, with one view and one
  // colour range for the sequence; they are replaced with the scene: both, or neither.
  // Empty: no maps.
  std::filesystem::path maps_dir;
  // A sequence whose frames share something (the default camera's box, a curvature view's or
  // the maps' colour ranges) keeps each analysed frame until the last one is read: in memory
  // up to this many bytes, beyond them in a temporary file in the staging directory. A frame
  // takes about 80 bytes a vertex, 160 with maps: a few small frames stay in memory, and a
  // long sequence of large frames never adds more than this to the peak.
  std::size_t frame_cache_bytes = std::size_t{16} << 20;
  // Leave out outline shell faces no ray can see (shell_culling.hpp). Off only to check that
  // leaving them out changes no pixel.
  bool cull_shells = true;
};

// generate_scene returns a PovgenReport (frame_result.hpp): each frame's FrameResult, and
// their sums.

// The passes over the frames that report progress: the survey (each frame read and analysed,
// where the sequence shares something, e.g. the default camera's box), then the frame loop
// (each frame's include written).
enum class PovgenPass : std::uint8_t { survey, frames };

// Called after each frame of a pass: the pass, frames done, frames in total.
using ProgressFn = std::function<void(PovgenPass, std::size_t, std::size_t)>;

// Frame selection, objects, a survey of the sequence where it shares something, then the frame
// loop: each water frame read and analysed once (frame_source.hpp), and written once, with its
// maps (from the survey's cache, frame_cache.hpp, where there is a survey).
// Throws InputError, ConfigError or OutputError; when `stop` becomes true it stops between
// frames and throws InterruptedError. On any failure DIR (and the maps) are left as they were.
PovgenReport generate_scene(const SceneConfig& config, const PovgenRequest& request,
                            const ProgressFn& progress, const std::atomic<bool>* stop);

}  // namespace toonwater
