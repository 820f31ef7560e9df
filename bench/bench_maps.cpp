// Curvature-map benchmarks on a generated 55k-vertex height field (235² grid,
// z = 0.1 sin 6x cos 6y) mapped at 1024² (target: writing the maps ≤ 0.2 s):
//   Plan        MapPlanner::add + view + ranges (extent, pixel size, robust ranges)
//   Rasterize   rasterize_top_down: coverage + barycentric resolve of all channels
//   WriteMaps   everything a frame costs after analysis: plan, rasterise, encode and write
//               the EXR and the three PNG previews (to the temp directory), into an empty
//               directory (replace:0) or over the previous frame's files (replace:1)
#include "analyzer/analysis.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/maps/map_planner.hpp"
#include "analyzer/maps/map_writer.hpp"

#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

const Analysis& wave_analysis() {
  static const Analysis analysis = [] {
    AnalyzeOptions options;
    options.flow.up = Axis::z;
    return analyze_mesh(make_wave_field(235, 0.1, 6.0, 1.0).mesh, options);
  }();
  return analysis;
}

MapOptions size_1024() {
  MapOptions options;
  options.size = 1024;
  return options;
}

void Plan(benchmark::State& state) {
  const Analysis& a = wave_analysis();
  for (auto _ : state) {
    MapPlanner planner(Axis::z);
    planner.add(a);
    benchmark::DoNotOptimize(planner.view(size_1024()));
    benchmark::DoNotOptimize(planner.ranges());
  }
}

void Rasterize(benchmark::State& state) {
  const Analysis& a = wave_analysis();
  MapPlanner planner(Axis::z);
  planner.add(a);
  const MapView view = planner.view(size_1024());
  for (auto _ : state) {
    const TopDownMap map =
        rasterize_top_down(a.surface, a.curvature, a.flow.label, a.flow.free_surface, view);
    benchmark::DoNotOptimize(map.covered_pixels);
  }
  state.counters["pixels"] = static_cast<double>(view.width) * view.height;
}

// `replace`: 0 writes into an empty directory (a first run), 1 replaces the previous files (a
// re-run; ext4 then flushes the replaced files' data on rename, which costs real time).
void WriteMaps(benchmark::State& state) {
  const Analysis& a = wave_analysis();
  const fs::path dir =
      fs::temp_directory_path() / ("toonwater-bench-maps-" + std::to_string(::getpid()));
  const bool replace = state.range(0) != 0;
  std::uintmax_t bytes = 0;
  for (auto _ : state) {
    if (!replace) {
      state.PauseTiming();
      fs::remove_all(dir);
      state.ResumeTiming();
    }
    MapFiles files;
    write_frame_maps(dir, "frame", a, Axis::z, size_1024(), &files);
    bytes = fs::file_size(files.exr);
  }
  state.counters["exr_MB"] = static_cast<double>(bytes) / 1e6;
  fs::remove_all(dir);
}

BENCHMARK(Plan)->Unit(benchmark::kMillisecond);
BENCHMARK(Rasterize)->Unit(benchmark::kMillisecond);
BENCHMARK(WriteMaps)
    ->Arg(0)
    ->Arg(1)
    ->ArgName("replace")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace
}  // namespace toonwater
