// The analysis with 1, 2 and 4 threads (oneTBB's global_control limit) gives the same bits:
// the mesh read from a file, its curvature, flow field, labels and counts, the strokes' field
// carried over from the frame before, and the CSV and PLY written. On a generated water tank
// large enough that every parallel pass splits into chunks at 4 threads.
#include "analyzer/analysis.hpp"
#include "analyzer/curvature_export.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/obj_writer.hpp"
#include "tests/analyzer/water_meshes.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace toonwater {
namespace {

using test::ScratchDir;

// A tank whose top is a wavy, irregularly jittered height field: 2 × 300² vertices.
TriangleMesh wavy_tank(double phase) {
  TriangleMesh mesh = test::tank(300, [phase](double x, double y) {
    return 0.1 * std::sin(6 * x + phase) * std::cos(6 * y) +
           0.02 * std::sin(17 * x + 5 * y - phase);
  });
  std::uint64_t state = 12345;
  for (Vec3& p : mesh.positions) {
    state = state * 6364136223846793005u + 1442695040888963407u;
    const double jitter = (static_cast<double>(state >> 11) * 0x1p-53 - 0.5) * 1e-3;
    p.x() += jitter;
    p.y() -= 0.5 * jitter;
  }
  return mesh;
}

// The bits of a vector of doubles, so that −0 and NaN compare as they are stored.
std::vector<std::uint64_t> bits(const std::vector<double>& values) {
  std::vector<std::uint64_t> out;
  out.reserve(values.size());
  for (double v : values) out.push_back(std::bit_cast<std::uint64_t>(v));
  return out;
}

// The tank stands on z, as the height fields of water_meshes.hpp.
AnalyzeOptions z_up() {
  AnalyzeOptions options;
  options.flow.up = Axis::z;
  return options;
}

struct Outputs {
  std::vector<std::uint64_t> gaussian, mean, area, field, carried_field;
  std::vector<std::int8_t> label, carried_label;
  std::vector<std::uint8_t> status, free_surface;
  std::size_t undefined = 0, extrapolated = 0, ridges = 0, valleys = 0, regions = 0;
  std::string csv, ply, jet_csv;
};

Outputs run_with_threads(int threads, const std::filesystem::path& obj) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<std::size_t>(threads));
  Outputs run;
  ScratchDir dir;
  const InputMesh input = read_mesh(obj);
  const std::vector<Triangle> triangles = input.mesh.triangles;
  const Analysis a = analyze_mesh(input.mesh, z_up());
  run.gaussian = bits(a.curvature.gaussian);
  run.mean = bits(a.curvature.mean);
  run.area = bits(a.curvature.area);
  run.field = bits(a.flow.field);
  run.label = a.flow.label;
  for (CurvatureStatus s : a.curvature.status) run.status.push_back(static_cast<std::uint8_t>(s));
  run.free_surface = a.flow.free_surface;
  run.undefined = a.curvature.undefined_vertices;
  run.extrapolated = a.curvature.extrapolated_vertices;
  run.ridges = a.flow.ridge_vertices;
  run.valleys = a.flow.valley_vertices;
  run.regions = a.flow.regions;
  write_curvature_csv(dir / "c.csv", a);
  run.csv = test::read_text(dir / "c.csv");
  write_curvature_ply(dir / "c.ply", triangles, a);
  run.ply = test::read_text(dir / "c.ply");

  // Two frames of a sequence: the second blends in the field carried from the first.
  FlowCoherence coherence;
  AnalyzeOptions sequence = z_up();
  sequence.coherence = &coherence;
  analyze_mesh(wavy_tank(0.0), sequence);
  const Analysis second = analyze_mesh(wavy_tank(0.05), sequence);
  run.carried_field = bits(second.flow.field);
  run.carried_label = second.flow.label;

  AnalyzeOptions jet = z_up();
  jet.estimator = Estimator::jet;
  jet.smoothing_steps = 2;
  write_curvature_csv(dir / "jet.csv", analyze_mesh(input.mesh, jet));
  run.jet_csv = test::read_text(dir / "jet.csv");
  return run;
}

TEST(ThreadCount, AnalysisIsBitIdenticalWithOneTwoAndFourThreads) {
  ScratchDir dir;
  write_obj(dir / "tank.obj", wavy_tank(0.0));
  const Outputs one = run_with_threads(1, dir / "tank.obj");
  ASSERT_GT(one.ridges + one.valleys, 0u) << "the tank must have flow labels to compare";
  for (int threads : {2, 4}) {
    SCOPED_TRACE(std::to_string(threads) + " threads");
    const Outputs other = run_with_threads(threads, dir / "tank.obj");
    EXPECT_EQ(other.gaussian, one.gaussian);
    EXPECT_EQ(other.mean, one.mean);
    EXPECT_EQ(other.area, one.area);
    EXPECT_EQ(other.status, one.status);
    EXPECT_EQ(other.free_surface, one.free_surface);
    EXPECT_EQ(other.field, one.field);
    EXPECT_EQ(other.label, one.label);
    EXPECT_EQ(other.undefined, one.undefined);
    EXPECT_EQ(other.extrapolated, one.extrapolated);
    EXPECT_EQ(other.ridges, one.ridges);
    EXPECT_EQ(other.valleys, one.valleys);
    EXPECT_EQ(other.regions, one.regions);
    EXPECT_EQ(other.carried_field, one.carried_field);
    EXPECT_EQ(other.carried_label, one.carried_label);
    EXPECT_TRUE(other.csv == one.csv) << "the CSVs differ";
    EXPECT_TRUE(other.ply == one.ply) << "the PLYs differ";
    EXPECT_TRUE(other.jet_csv == one.jet_csv) << "the jet estimator's CSVs differ";
  }
}

}  // namespace
}  // namespace toonwater
