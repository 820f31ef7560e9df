// Curvature estimators on jittered height fields z = A sin(kx) cos(ky) of about 55k and 1M
// vertices (analyzer/curvature.hpp, curvature_jet.hpp, curvature_smoothing.hpp):
//   OneRing      compute_curvature (the default)
//   Jet          compute_curvature_jet (includes the one-ring pass for normals and areas)
//   Smoothing2   two smoothing steps of an already computed field
// report/README.md quotes the figures.
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/curvature_jet.hpp"
#include "analyzer/curvature_smoothing.hpp"

#include <benchmark/benchmark.h>

#include <map>

namespace toonwater {
namespace {

struct Prepared {
  TriangleMesh mesh;
  MeshTopology topology;
};

// 235² ≈ 55k vertices, 1000² = 1M; vertices jittered by 0.2 of the grid step.
const Prepared& jittered_wave(std::int64_t vertices) {
  static std::map<std::int64_t, Prepared> cache;
  auto it = cache.find(vertices);
  if (it == cache.end()) {
    Prepared p;
    p.mesh = make_wave_field(vertices == 55 ? 235 : 1000, 0.1, 6.0, 1.0, {0.2, 7}).mesh;
    p.topology = analyze_topology(p.mesh);
    it = cache.emplace(vertices, std::move(p)).first;
  }
  return it->second;
}

void set_vertex_rate(benchmark::State& state, std::size_t vertices) {
  state.counters["vertices"] = static_cast<double>(vertices);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * vertices));
}

void OneRing(benchmark::State& state) {
  const Prepared& p = jittered_wave(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(compute_curvature(p.mesh, p.topology));
  set_vertex_rate(state, p.mesh.positions.size());
}

void Jet(benchmark::State& state) {
  const Prepared& p = jittered_wave(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(compute_curvature_jet(p.mesh, p.topology));
  set_vertex_rate(state, p.mesh.positions.size());
}

void Smoothing2(benchmark::State& state) {
  const Prepared& p = jittered_wave(state.range(0));
  const CurvatureField computed = compute_curvature(p.mesh, p.topology);
  for (auto _ : state) {
    state.PauseTiming();
    CurvatureField field = computed;
    state.ResumeTiming();
    smooth_curvature(p.mesh, p.topology.vertex_faces, field, 2);
    benchmark::DoNotOptimize(field);
  }
  set_vertex_rate(state, p.mesh.positions.size());
}

// Arguments: 55 → 55k vertices, 1000 → 1M vertices.
BENCHMARK(OneRing)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Jet)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);
BENCHMARK(Smoothing2)->Arg(55)->Arg(1000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace toonwater
