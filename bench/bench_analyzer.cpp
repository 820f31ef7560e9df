// Analyzer benchmarks on generated height fields z = A sin(kx) cos(ky) of about 55k and 1M
// vertices (the paper's frame had 55,091). Stages are timed separately:
//   ReadObj          read_mesh of an OBJ file written once to the temp directory
//   ReadPly          read_mesh of the same mesh as a binary PLY of float coordinates (what the
//                    whole-process comparisons with MeshLab read)
//   Prepare          weld + topology + orientation
//   Curvature        compute_curvature
//   FlowRegions      find_flow_regions: the flow field, its smoothing, fading and labels
//   FlowWithCoherence  the same blended with a previous frame (flow_coherence.hpp): the whole
//                    flow stage of a sequence frame in povgen
//   CurvatureAndLabels  compute_curvature and FlowRegions together
//   CurvatureAndFlowStage  compute_curvature and FlowWithCoherence together: the figure the
//                    targets are stated for
//   AnalyzeCommand   `toonwater analyze MESH --csv FILE` end to end as a child process, with
//                    its peak resident memory per vertex (counter bytes_per_vertex)
// and frame 15 of a Mantaflow bake, as issue #32 compares its inputs: the mesh cache against the
// level set of the data cache. The bake is the directory TOONWATER_BENCH_BAKE names (with mesh/
// and data/: the cache folder of mantaflow_bake.py's bakes), else the shared dam break's cache.
//   BakeFrame/0      read_mesh of mesh/fluid_mesh_0015.bobj.gz, then analyze_mesh
//   BakeFrame/1      read_mesh of data/fluid_data_0015.vdb: reading and meshing the level set
//   BakeFrame/2      read_mesh of data/fluid_data_0015.vdb, then analyze_mesh
#include "analyzer/analysis.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/obj_writer.hpp"
#include "analyzer/weld.hpp"

#include <benchmark/benchmark.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <bit>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <filesystem>
#include <map>
#include <string>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// n×n grid: 235² ≈ 55k vertices, 1000² = 1M.
int grid_size(std::int64_t vertices) { return vertices == 55 ? 235 : 1000; }

const TriangleMesh& wave_mesh(std::int64_t vertices) {
  static std::map<std::int64_t, TriangleMesh> cache;
  auto it = cache.find(vertices);
  if (it == cache.end())
    it = cache.emplace(vertices, make_wave_field(grid_size(vertices), 0.1, 6.0, 1.0).mesh).first;
  return it->second;
}

fs::path obj_file(std::int64_t vertices) {
  const fs::path path = fs::temp_directory_path() /
                        ("toonwater-bench-wave-" + std::to_string(grid_size(vertices)) + ".obj");
  if (fs::exists(path)) return path;
  write_obj(path, wave_mesh(vertices));
  return path;
}

// Binary little-endian PLY, float x, y, z and uchar/int index lists, as exporters write it.
fs::path ply_file(std::int64_t vertices) {
  const fs::path path = fs::temp_directory_path() /
                        ("toonwater-bench-wave-" + std::to_string(grid_size(vertices)) + ".ply");
  if (fs::exists(path)) return path;
  static_assert(std::endian::native == std::endian::little, "writes the values' own bytes");
  const TriangleMesh& mesh = wave_mesh(vertices);
  std::string bytes = "ply\nformat binary_little_endian 1.0\nelement vertex " +
                      std::to_string(mesh.positions.size()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(mesh.triangles.size()) +
                      "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const Vec3& p : mesh.positions)
    for (int axis = 0; axis < 3; ++axis) {
      const auto value = static_cast<float>(p[axis]);
      bytes.append(reinterpret_cast<const char*>(&value), sizeof value);
    }
  for (const Triangle& t : mesh.triangles) {
    bytes.push_back(3);
    bytes.append(reinterpret_cast<const char*>(t.data()), sizeof t);
  }
  const fs::path partial = path.string() + ".partial";
  std::FILE* out = std::fopen(partial.c_str(), "wb");
  if (!out || std::fwrite(bytes.data(), 1, bytes.size(), out) != bytes.size() ||
      std::fclose(out) != 0)
    throw std::runtime_error("cannot write " + partial.string());
  fs::rename(partial, path);
  return path;
}

void set_vertex_rate(benchmark::State& state, std::size_t vertices) {
  state.counters["vertices"] = static_cast<double>(vertices);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * vertices));
}

// read_mesh of one file over and over.
void read_repeatedly(benchmark::State& state, const fs::path& path) {
  std::size_t n = 0;
  for (auto _ : state) {
    InputMesh mesh = read_mesh(path);
    n = mesh.mesh.positions.size();
    benchmark::DoNotOptimize(mesh);
  }
  set_vertex_rate(state, n);
}

void ReadObj(benchmark::State& state) { read_repeatedly(state, obj_file(state.range(0))); }

void ReadPly(benchmark::State& state) { read_repeatedly(state, ply_file(state.range(0))); }

void Prepare(benchmark::State& state) {
  const TriangleMesh& input = wave_mesh(state.range(0));
  for (auto _ : state) {
    WeldedMesh welded = weld_coincident_vertices(input);
    MeshTopology topology = analyze_topology(welded.mesh);
    benchmark::DoNotOptimize(orient_consistently(welded.mesh, topology));
  }
  set_vertex_rate(state, input.positions.size());
}

struct Prepared {
  TriangleMesh mesh;
  MeshTopology topology;
};

Prepared prepared(std::int64_t vertices) {
  Prepared p{wave_mesh(vertices), {}};
  p.topology = analyze_topology(p.mesh);
  return p;
}

FlowOptions wave_flow_options() {
  FlowOptions options;
  options.up = Axis::z;
  return options;
}

void Curvature(benchmark::State& state) {
  const Prepared p = prepared(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(compute_curvature(p.mesh, p.topology));
  set_vertex_rate(state, p.mesh.positions.size());
}

void FlowRegions(benchmark::State& state) {
  const Prepared p = prepared(state.range(0));
  const CurvatureField field = compute_curvature(p.mesh, p.topology);
  for (auto _ : state)
    benchmark::DoNotOptimize(find_flow_regions(p.mesh, p.topology, field, wave_flow_options()));
  set_vertex_rate(state, p.mesh.positions.size());
}

void FlowWithCoherence(benchmark::State& state) {
  const Prepared p = prepared(state.range(0));
  const CurvatureField field = compute_curvature(p.mesh, p.topology);
  FlowCoherence coherence;
  find_flow_regions(p.mesh, p.topology, field, wave_flow_options(), &coherence);
  for (auto _ : state)
    benchmark::DoNotOptimize(
        find_flow_regions(p.mesh, p.topology, field, wave_flow_options(), &coherence));
  set_vertex_rate(state, p.mesh.positions.size());
}

void CurvatureAndLabels(benchmark::State& state) {
  const Prepared p = prepared(state.range(0));
  for (auto _ : state) {
    const CurvatureField field = compute_curvature(p.mesh, p.topology);
    benchmark::DoNotOptimize(find_flow_regions(p.mesh, p.topology, field, wave_flow_options()));
  }
  set_vertex_rate(state, p.mesh.positions.size());
}

void CurvatureAndFlowStage(benchmark::State& state) {
  const Prepared p = prepared(state.range(0));
  FlowCoherence coherence;
  find_flow_regions(p.mesh, p.topology, compute_curvature(p.mesh, p.topology), wave_flow_options(),
                    &coherence);
  for (auto _ : state) {
    const CurvatureField field = compute_curvature(p.mesh, p.topology);
    benchmark::DoNotOptimize(
        find_flow_regions(p.mesh, p.topology, field, wave_flow_options(), &coherence));
  }
  set_vertex_rate(state, p.mesh.positions.size());
}

void AnalyzeCommand(benchmark::State& state) {
  const fs::path mesh = obj_file(state.range(0));
  const fs::path csv = fs::temp_directory_path() / "toonwater-bench-analyze.csv";
  long peak_kib = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::freopen("/dev/null", "w", stderr);
      ::execl(TOONWATER_EXECUTABLE, "toonwater", "analyze", mesh.c_str(), "--up", "z", "--csv",
              csv.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    int status = 0;
    rusage usage{};
    ::wait4(pid, &status, 0, &usage);
    state.SetIterationTime(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
      state.SkipWithError("toonwater analyze failed");
    peak_kib = std::max(peak_kib, usage.ru_maxrss);
  }
  const auto n = static_cast<double>(wave_mesh(state.range(0)).positions.size());
  state.counters["vertices"] = n;
  state.counters["bytes_per_vertex"] = static_cast<double>(peak_kib) * 1024.0 / n;
  fs::remove(csv);
}

void BakeFrame(benchmark::State& state) {
  const char* bake = std::getenv("TOONWATER_BENCH_BAKE");
  const fs::path cache =
      bake ? fs::path(bake) : fs::path(TOONWATER_SHARED_DIR) / "data/mantaflow-dambreak/cache";
  const fs::path path = state.range(0) == 0 ? cache / "mesh/fluid_mesh_0015.bobj.gz"
                                            : cache / "data/fluid_data_0015.vdb";
  if (!fs::exists(path)) {
    state.SkipWithError(("no " + path.string()).c_str());
    return;
  }
  AnalyzeOptions options;
  options.flow.up = Axis::z;
  std::size_t n = 0;
  for (auto _ : state) {
    InputMesh input = read_mesh(path);
    n = input.mesh.positions.size();
    if (state.range(0) == 1)
      benchmark::DoNotOptimize(input);
    else
      benchmark::DoNotOptimize(analyze_mesh(std::move(input.mesh), options));
  }
  set_vertex_rate(state, n);
}

// Arguments: 55 → 55k vertices, 1000 → 1M vertices.
BENCHMARK(ReadObj)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(ReadPly)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Prepare)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Curvature)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(FlowRegions)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(FlowWithCoherence)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(CurvatureAndLabels)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(CurvatureAndFlowStage)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(AnalyzeCommand)->Arg(1000)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);
BENCHMARK(BakeFrame)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace toonwater
