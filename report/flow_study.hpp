// The flow criteria compared (analyzer/flow_regions.hpp: `mean`, the default, and `paper`):
//
// 1. Analytic concentric ripples, z = a cos(k r) out to two wavelengths and calm beyond
//    (a = 0.5 % and λ = 15 % of the 2 × 2 sheet), on regular grids at several resolutions and
//    on jittered ones: the share of vertices near each crest circle labelled ridge and near
//    each trough circle labelled valley, the labelled share of calm water, and the labelled
//    share of the whole sheet (which a resolution-free criterion keeps under refinement).
// 2. A real sequence seen from straight above (povgen's scene with an overhead camera, flat
//    ridge and valley colours, rendered by POV-Ray at `pixels_per_cell` pixels per median edge
//    length), measured on the rendered pixels: frames with regions, the share of flow pixels in
//    pieces under 4 cells² (specks), and the boundary roughness — the length of the region
//    boundaries (traced through the pixel centres) against their length after a box blur one
//    cell wide (a staircase along mesh edges is long against its smoothed self; a smooth
//    curve is not).
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"
#include "scene/config.hpp"
#include "report/image.hpp"

#include <array>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::report {

// The ripple sheet on an n × n grid over [−1, 1]², z up, x and y jittered by up to `jitter`
// grid steps (the border stays straight).
TriangleMesh ripple_mesh(int n, double jitter);

struct RippleCoverage {
  double crest_ridge = 0;     // share of the vertices within 0.08 λ of a crest circle
  double trough_valley = 0;   // likewise for the trough circles and valley
  double calm_labelled = 0;   // share of the calm water's vertices (beyond 3 λ) labelled
  double labelled_share = 0;  // labelled area over the sheet's area
};

RippleCoverage ripple_coverage(const Analysis& ripple);

struct RippleRow {
  std::string criterion;
  int n = 0;
  bool jittered = false;
  RippleCoverage coverage;
};

std::vector<RippleRow> run_ripple_study(const std::vector<int>& resolutions);

// A rendered picture split into flow classes: 1 ridge, −1 valley, 0 anything else.
struct FlowMask {
  int width = 0, height = 0;
  std::vector<std::int8_t> classes;
};

// Pixels within `tolerance` (per channel, as encoded) of the ridge or valley colour.
FlowMask flow_mask(const Image& image, const std::array<float, 3>& ridge,
                   const std::array<float, 3>& valley, float tolerance = 0.02f);

struct FlowPictureMetrics {
  std::size_t flow_pixels = 0;
  double speck_share = 0;     // of the flow pixels, in 4-connected pieces under 4 cells²
  double boundary_ratio = 0;  // boundary length over its one-cell-smoothed length (0: none)
};

FlowPictureMetrics measure_flow_mask(const FlowMask& mask, double pixels_per_cell);

struct SequenceFlowStudy {
  std::string criterion;
  std::size_t frames = 0;
  std::size_t frames_with_regions = 0;
  double speck_share = 0;     // all frames' flow pixels together
  double boundary_ratio = 0;  // median over the frames with regions
  std::map<long, std::size_t> flow_pixels_by_frame;
  std::filesystem::path picture;  // one rendered frame (the middle one)
};

// Renders the water sequence `pattern` (up axis `up`; `frames` of it, default all) from straight
// above with each criterion's regions in flat red (ridge) and green (valley), coherence on, and
// measures every frame. Scenes and frames go under `work_dir`; the middle frame is copied to
// `picture_dir` as flow_<criterion>.png. Throws std::runtime_error when a frame fails to render.
std::vector<SequenceFlowStudy> run_sequence_flow_study(
    const std::string& pattern, Axis up, const std::filesystem::path& work_dir,
    const std::filesystem::path& picture_dir, double pixels_per_cell,
    const std::vector<FlowCriterion>& criteria = {FlowCriterion::mean, FlowCriterion::paper},
    std::optional<FrameRange> frames = {});

}  // namespace toonwater::report
