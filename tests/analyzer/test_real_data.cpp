// The analyzer on real simulation output from ../shared/data (skipped where it is absent):
// a Blender Mantaflow sequence (closed liquid volume, Z up) and a Blender FFT ocean (open sheet).
#include "analyzer/analysis.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/noise_floor.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

namespace toonwater::test {
namespace {

std::filesystem::path data_file(const std::string& relative) {
  const std::filesystem::path shared = shared_dir();
  if (shared.empty()) return {};
  return shared / "data" / relative;
}

Analysis analyze_z_up(const std::filesystem::path& path) {
  AnalyzeOptions options;
  options.flow.up = Axis::z;
  return analyze_mesh(read_mesh(path).mesh, options);
}

class MantaflowFrame : public testing::TestWithParam<int> {};

TEST_P(MantaflowFrame, ClosedVolumeWallsAndFloorCarryNoFlowRegions) {
  char name[64];
  std::snprintf(name, sizeof name, "mantaflow-wake/water_%04d.obj", GetParam());
  const auto path = data_file(name);
  if (path.empty()) GTEST_SKIP() << "../shared/data is absent: real-data tests skipped";
  const Analysis a = analyze_z_up(path);
  EXPECT_EQ(a.topology.boundary_vertices, 0u) << "the liquid volume is closed";
  EXPECT_EQ(a.flipped_faces, 0u);
  EXPECT_TRUE(all_finite(a.curvature));
  // The surface rests at z ≈ 0.2263 (data README); the floor and walls must not pull it away.
  EXPECT_NEAR(a.flow.rest_height, 0.2263, 0.01);
  std::size_t labelled = 0;
  for (std::size_t v = 0; v < a.surface.positions.size(); ++v) {
    const Vec3& p = a.surface.positions[v];
    const bool wall_or_floor = std::abs(p.x()) > 0.98 || std::abs(p.y()) > 0.48 || p.z() < 0.02;
    if (wall_or_floor) {
      EXPECT_EQ(a.flow.label[v], FlowLabel::none) << p.transpose();
    }
    labelled += a.flow.label[v] != FlowLabel::none;
  }
  EXPECT_GT(a.flow.ridge_vertices, 0u);
  EXPECT_GT(a.flow.valley_vertices, 0u);
  EXPECT_LT(labelled, a.flow.free_surface_vertices / 5) << "flow regions are features, not the sea";
}

INSTANTIATE_TEST_SUITE_P(Frames, MantaflowFrame, testing::Values(1, 15, 25, 30),
                         [](const testing::TestParamInfo<int>& frame) {
                           return "frame_" + std::to_string(frame.param);
                         });

// An FFT ocean's chop runs down to its grid's spacing: at the scale of the cells it is noise,
// so the threshold rises above it (flow_regions.hpp) and what was confetti of 200 regions over
// the whole tile (from above, 32 % of its pixels) leaves at most the few most salient crests,
// above the rest level; its swells still tilt the shading normals, so the bands show them.
TEST(BlenderOcean, OpenSheetHasABoundaryRimAndItsChopIsBelowTheNoiseFloor) {
  const auto path = data_file("blender-ocean/water_0001.obj");
  if (path.empty()) GTEST_SKIP() << "../shared/data is absent: real-data tests skipped";
  const Analysis a = analyze_z_up(path);
  EXPECT_EQ(a.surface.positions.size(), 38809u);
  EXPECT_EQ(a.topology.boundary_vertices, 4u * 196u);  // 197 × 197 grid rim
  EXPECT_TRUE(all_finite(a.curvature));
  EXPECT_EQ(a.flow.walls, 0u) << "an open sheet has no tank walls";
  EXPECT_GT(a.flow.threshold, 2.0 / a.flow.scale_length) << "the noise floor is binding";
  EXPECT_DOUBLE_EQ(a.flow.threshold, 3.0 * a.flow.sequence_noise_floor);
  EXPECT_LE(a.flow.regions, flow_defaults(FlowCriterion::mean).max_regions);
  EXPECT_LT(a.flow.ridge_vertices + a.flow.valley_vertices, a.surface.positions.size() / 100);
  double ridge_height = 0;
  for (std::size_t v = 0; v < a.surface.positions.size(); ++v)
    if (a.flow.label[v] == FlowLabel::ridge) ridge_height += a.surface.positions[v].z();
  if (a.flow.ridge_vertices > 0) {
    EXPECT_GT(ridge_height / static_cast<double>(a.flow.ridge_vertices), a.flow.rest_height);
  }
  std::vector<double> tilt;
  for (const Vec3& n : a.flow.shading_normal) tilt.push_back(n.x());
  const std::vector<std::uint8_t> all(tilt.size(), 1);
  EXPECT_GT(robust_spread(tilt, all), 0.05) << "the swells tilt the shading normals";
  EXPECT_LT(a.flow.normal_noise, 0.2 * robust_spread(tilt, all)) << "and that is not noise";
}

}  // namespace
}  // namespace toonwater::test
