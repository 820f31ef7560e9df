// povgen speed (issue 3): a 55k-vertex frame analysed and written (target <= 0.1 s), a
// 1M-vertex mesh2 written (target <= 0.5 s), and POV-Ray's own parse and trace times on
// generated scenes at 640x480 with refraction (BM_Povray*, slow: not for CI; run them with
// --benchmark_filter=Povray).
#include "analyzer/analytic_surfaces.hpp"
#include "analyzer/atomic_file.hpp"
#include "povgen/config.hpp"
#include "povgen/mesh2_writer.hpp"
#include "povgen/povgen.hpp"
#include "povgen/scene_writer.hpp"

#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace toonwater;

// n×n height field z = A sin(kx) cos(ky): n = 235 gives 55,225 vertices, n = 1000 one million.
TriangleMesh wave_field(int n) { return make_wave_field(n, 0.1, 6.0, 1.0).mesh; }

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() /
                       ("toonwater-bench-" + std::to_string(::getpid()) + "-" + name);
  fs::create_directories(dir);
  return dir;
}

void BM_PovgenFrame(benchmark::State& state) {
  const TriangleMesh mesh = wave_field(static_cast<int>(state.range(0)));
  const povgen::SceneConfig config;
  const povgen::LightGeometry light = povgen::light_geometry(config.light, Axis::z);
  const fs::path dir = scratch("frame");
  double analysis = 0, writing = 0;
  for (auto _ : state) {
    const auto s = povgen::prepare_surface(mesh, Axis::z, &config.flow, nullptr);
    const auto start = std::chrono::steady_clock::now();
    const povgen::CameraPlacement camera =
        povgen::frame_camera(config, Axis::z, s.mesh.min, s.mesh.max);
    const std::string text = povgen::mesh_include(
        s, "Water", light, povgen::shell_offsets(config.outline, s.mesh, camera, config.render.width));
    write_file_atomically(dir / "water_0001.inc", text);
    writing += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    analysis += s.analysis_seconds;
  }
  state.counters["vertices"] = static_cast<double>(mesh.positions.size());
  state.counters["analysis_s"] = benchmark::Counter(analysis, benchmark::Counter::kAvgIterations);
  state.counters["writing_s"] = benchmark::Counter(writing, benchmark::Counter::kAvgIterations);
  fs::remove_all(dir);
}
BENCHMARK(BM_PovgenFrame)->Arg(235)->Arg(707)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Mesh2Write(benchmark::State& state) {
  const TriangleMesh mesh = wave_field(static_cast<int>(state.range(0)));
  std::vector<Vec3> normals(mesh.positions.size(), Vec3(0, 0, 1));
  const auto sm = povgen::make_scene_mesh(mesh, normals, false, Axis::z);
  const auto uv = povgen::toon_coordinates(sm, {}, {});
  const fs::path dir = scratch("mesh2");
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string text;
    povgen::append_mesh2(text, "Water_mesh", sm, uv);
    write_file_atomically(dir / "water.inc", text);
    bytes = text.size();
  }
  state.counters["vertices"] = static_cast<double>(mesh.positions.size());
  state.counters["bytes"] = static_cast<double>(bytes);
  fs::remove_all(dir);
}
BENCHMARK(BM_Mesh2Write)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

// POV-Ray's statistics: "Parse Time: ... (0.812 seconds)".
double povray_seconds(const std::string& log, const std::string& what) {
  std::smatch m;
  if (std::regex_search(log, m, std::regex(what + R"( Time:.*\(([0-9.]+) seconds\))")))
    return std::stod(m[1]);
  return -1;
}

void BM_PovrayRender(benchmark::State& state) {
  // A wave field as the water (flow regions, outlines, reflection and refraction on) with a
  // submerged sphere, written by povgen, rendered at 640x480 without antialiasing.
  const int n = static_cast<int>(state.range(0));
  const fs::path dir = scratch("povray" + std::to_string(n));
  const TriangleMesh water = wave_field(n);
  {
    std::string obj;
    for (const Vec3& p : water.positions)
      obj += "v " + std::to_string(p.x()) + " " + std::to_string(p.y()) + " " + std::to_string(p.z()) + "\n";
    for (const Triangle& t : water.triangles)
      obj += "f " + std::to_string(t[0] + 1) + " " + std::to_string(t[1] + 1) + " " +
             std::to_string(t[2] + 1) + "\n";
    write_file_atomically(dir / "water.obj", obj);
  }
  povgen::ConfigSources sources;
  sources.overrides = {"render.antialias=false"};
  const povgen::SceneConfig config = povgen::load_config(sources);
  povgen::PovgenRequest request;
  request.water_pattern = (dir / "water.obj").string();
  request.up = Axis::z;
  request.out_dir = dir / "scene";
  povgen::generate_scene(config, request, {}, nullptr);

  double parse = 0, trace = 0;
  for (auto _ : state) {
    const std::string command = "cd '" + request.out_dir.string() + "' && povray scene.ini 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string log;
    char buffer[4096];
    for (std::size_t k; (k = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) log.append(buffer, k);
    if (::pclose(pipe) != 0) state.SkipWithError("povray failed");
    parse += povray_seconds(log, "Parse");
    trace += povray_seconds(log, "Trace");
  }
  state.counters["vertices"] = static_cast<double>(water.positions.size());
  state.counters["parse_s"] = benchmark::Counter(parse, benchmark::Counter::kAvgIterations);
  state.counters["trace_s"] = benchmark::Counter(trace, benchmark::Counter::kAvgIterations);
  fs::remove_all(dir);
}
// 55,225 and 499,849 vertices.
BENCHMARK(BM_PovrayRender)->Arg(235)->Arg(707)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
