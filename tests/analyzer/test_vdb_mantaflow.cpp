// A real Mantaflow bake's liquid level set (../shared/data/mantaflow-dambreak, cache/data) read
// with the same --scale and --translate as its mesh cache lands on Mantaflow's own mesh of the
// frame (water_NNNN.obj, world coordinates), on every frame that has both, walls included:
// nearest-vertex distances both ways, in cells (issue #32: median ≤ 1, 95th percentile ≤ 2).
#include "analyzer/affine_transform.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/point_grid.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace toonwater::test {
namespace {

constexpr double cell = 0.01875;  // the bake's voxel (README)

// Distances in cells from each of `from`'s vertices to the closest vertex of `to` (5 cells when
// none is that close).
std::vector<double> distances(const TriangleMesh& from, const TriangleMesh& to) {
  const PointGrid grid(to.positions, 5 * cell);
  std::vector<double> out;
  for (const Vec3& p : from.positions) {
    const std::int32_t c = grid.closest(p);
    out.push_back(c < 0 ? 5.0 : (to.positions[c] - p).norm() / cell);
  }
  std::sort(out.begin(), out.end());
  return out;
}

double quantile(const std::vector<double>& sorted, double q) {
  return sorted[static_cast<std::size_t>(q * static_cast<double>(sorted.size() - 1))];
}

TEST(VdbMantaflow, TheLiquidLevelSetLiesOnMantaflowsMeshWithTheMeshCachesMapping) {
  const std::filesystem::path shared = shared_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/data is absent: real-data test skipped";
  const std::filesystem::path bake = shared / "data" / "mantaflow-dambreak";
  // The mesh cache's mapping (README): world = (0, 0, 0.3) + 1.2 v.
  const AffineTransform to_world = scale_then_translate(1.2, Vec3(0, 0, 0.3));
  for (int frame = 10; frame <= 20; ++frame) {
    char data[64], water[64];
    std::snprintf(data, sizeof data, "cache/data/fluid_data_%04d.vdb", frame);
    std::snprintf(water, sizeof water, "water_%04d.obj", frame);
    TriangleMesh phi = read_mesh(bake / data).mesh;
    apply_transform(to_world, phi, bake / data);
    const TriangleMesh mantaflow = read_mesh(bake / water).mesh;
    // Closed at the walls as Mantaflow closes its mesh: inside the tank (README), not beyond it.
    for (const Vec3& p : phi.positions)
      ASSERT_TRUE(std::abs(p.x()) < 0.6 && std::abs(p.y()) < 0.3 && p.z() > 0 && p.z() < 0.6)
          << "frame " << frame << ": (" << p.transpose() << ") lies outside the tank";
    for (const auto& [name, d] :
         {std::pair{"phi to Mantaflow's mesh", distances(phi, mantaflow)},
          std::pair{"Mantaflow's mesh to phi", distances(mantaflow, phi)}}) {
      SCOPED_TRACE(std::string(name) + ", frame " + std::to_string(frame));
      ASSERT_GT(d.size(), 1000u);
      EXPECT_LE(quantile(d, 0.5), 1.0);
      EXPECT_LE(quantile(d, 0.95), 2.0);
    }
  }
}

}  // namespace
}  // namespace toonwater::test
