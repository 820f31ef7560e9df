// overhead_study: issue #28's measures on any bake, from straight above at 640×400 with every
// band and region in a pure colour (report/overhead_study.hpp), one line a frame, then the
// medians the targets are stated for, and the regions' boundary roughness at 8 pixels a cell
// (report/flow_study.hpp). What the tests assert on ../shared/data
// (tests/report/test_flow_study.cpp), for bakes that are not there (mantaflow_bake.py's ball-drop).
//
//   overhead_study [--frames FIRST-LAST] [--strokes] WATER CELL X0,Y0,Z0,X1,Y1,Z1 [OBJECT ...]
//
// --strokes measures issue #29's stroke steadiness instead (run_stroke_study): one line a
// frame, then the median shares of stroke pixels lost (none within 2 px in the next frame) and
// gone (none within a cell).
//
// WATER and OBJECT are file patterns (####: the frame) in one coordinate system, Z up; CELL is
// the simulation's cell; the box is the tank (its sides across Z are walls, Z1 about the water's
// rest level). Scenes and frames go to a temporary directory, kept when TOONWATER_KEEP names one.
#include "report/flow_study.hpp"
#include "report/overhead_study.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using toonwater::report::OverheadFrame;

std::size_t median(std::vector<std::size_t> values) {
  if (values.empty()) return 0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

double median_share(std::vector<double> values) {
  if (values.empty()) return 0;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

int stroke_study(const std::string& pattern, const toonwater::report::OverheadOptions& options,
                 const fs::path& work) {
  const std::vector<toonwater::report::StrokeFrame> frames =
      toonwater::report::run_stroke_study(pattern, options, work);
  std::vector<double> lost, gone;
  std::vector<std::size_t> strokes, pieces;
  std::size_t drawn = 0;
  std::printf("frame,stroke_pixels,strokes,stroke_pieces,lost_share,gone_share\n");
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const toonwater::report::StrokeFrame& f = frames[i];
    std::printf("%ld,%zu,%zu,%zu,%.4f,%.4f\n", f.frame, f.stroke_pixels, f.strokes, f.stroke_pieces,
                f.lost_share, f.gone_share);
    if (i + 1 < frames.size() && f.stroke_pixels > 0) {
      lost.push_back(f.lost_share);
      gone.push_back(f.gone_share);
    }
    strokes.push_back(f.strokes);
    pieces.push_back(f.stroke_pieces);
    drawn += f.stroke_pixels > 0;
  }
  std::printf(
      "# %zu frames, strokes drawn in %zu; median share of stroke pixels lost %.3f, gone "
      "%.3f; median strokes %zu, in %zu pieces\n",
      frames.size(), drawn, median_share(lost), median_share(gone), median(strokes),
      median(pieces));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  bool strokes = false;
  std::optional<toonwater::FrameRange> range;
  while (!args.empty() && args.front().rfind("--", 0) == 0) {
    if (args.front() == "--strokes") {
      strokes = true;
      args.erase(args.begin());
    } else if (args.front() == "--frames" && args.size() > 1) {
      try {
        range = toonwater::parse_frame_range(args[1], "--frames");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "overhead_study: %s\n", e.what());
        return 2;
      }
      args.erase(args.begin(), args.begin() + 2);
    } else {
      std::fprintf(stderr, "overhead_study: unknown option %s\n", args.front().c_str());
      return 2;
    }
  }
  if (args.size() < 3) {
    std::fprintf(stderr,
                 "usage: overhead_study [--frames FIRST-LAST] [--strokes] WATER CELL "
                 "X0,Y0,Z0,X1,Y1,Z1 [OBJECT ...]\n");
    return 2;
  }
  try {
    toonwater::report::OverheadOptions options;
    options.frames = range;
    options.up = toonwater::Axis::z;
    options.cell = std::stod(args[1]);
    std::istringstream box(args[2]);
    double b[6];
    char comma = ',';
    for (int i = 0; i < 6; ++i)
      if (!(box >> b[i]) || (i < 5 && !(box >> comma)) || comma != ',')
        throw std::invalid_argument("the tank is X0,Y0,Z0,X1,Y1,Z1, not " + args[2]);
    options.tank_min = toonwater::Vec3(b[0], b[1], b[2]);
    options.tank_max = toonwater::Vec3(b[3], b[4], b[5]);
    for (std::size_t i = 3; i < args.size(); ++i) options.objects.push_back(args[i]);
    const char* keep = std::getenv("TOONWATER_KEEP");
    const fs::path work =
        keep ? fs::path(keep)
             : fs::temp_directory_path() / ("toonwater-overhead-" + std::to_string(::getpid()));
    if (strokes) {
      const int status = stroke_study(args[0], options, work);
      if (!keep) fs::remove_all(work);
      return status;
    }
    const std::vector<OverheadFrame> frames =
        toonwater::report::run_overhead_study(args[0], options, work);
    const std::vector<toonwater::report::SequenceFlowStudy> roughness =
        toonwater::report::run_sequence_flow_study(args[0], options.up, work / "roughness",
                                                   work / "roughness", 8.0,
                                                   {toonwater::FlowCriterion::mean});
    if (!keep) fs::remove_all(work);
    std::size_t flow = 0, wall_flow = 0;
    std::vector<std::size_t> pieces, specks;
    std::printf("frame,flow_share,changed_share,flow_pieces,band_specks,bright_dark_share\n");
    for (const OverheadFrame& f : frames) {
      std::printf("%ld,%.4f,%.4f,%zu,%zu,%.4f\n", f.frame, f.flow_share(), f.changed_share,
                  f.flow_pieces, f.band_specks, f.contrast_share);
      flow += f.flow_pixels;
      wall_flow += f.wall_flow_pixels;
      pieces.push_back(f.flow_pieces);
      specks.push_back(f.band_specks);
    }
    std::printf(
        "# %zu frames; flow within 4 cells of the walls %.4f of all flow; median flow pieces %zu, "
        "median band specks %zu\n",
        frames.size(), flow ? static_cast<double>(wall_flow) / static_cast<double>(flow) : 0.0,
        median(pieces), median(specks));
    std::printf(
        "# at 8 pixels a cell: regions in %zu of %zu frames, boundary length %.3f times "
        "its one-cell-smoothed length (median), flow pixels in specks %.4f\n",
        roughness.at(0).frames_with_regions, roughness.at(0).frames, roughness.at(0).boundary_ratio,
        roughness.at(0).speck_share);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "overhead_study: error: %s\n", e.what());
    return 1;
  }
}
