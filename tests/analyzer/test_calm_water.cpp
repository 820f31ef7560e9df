// Calm water stays calm: the noise floor of the flow field, the tank's walls and the salience
// limit (flow_regions.hpp, noise_floor.hpp, tank_walls.hpp), on closed tanks whose free surface
// carries known noise and waves.
#include "analyzer/flow_regions.hpp"
#include "analyzer/noise_floor.hpp"
#include "analyzer/tank_walls.hpp"
#include "tests/analyzer/curvature_test_util.hpp"
#include "tests/analyzer/flow_test_util.hpp"
#include "tests/analyzer/water_meshes.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

namespace toonwater::test {
namespace {

constexpr int kGrid = 101;                   // vertices along a side of the tank's top
constexpr double kCell = 2.0 / (kGrid - 1);  // its spacing: the "cell" of these tanks

// A fixed pseudo-random value in [−1, 1) for a grid point: marching-cubes-like jitter, which
// changes from vertex to vertex and is the same in every run.
double jitter(double x, double y) {
  const auto i = static_cast<std::uint64_t>(std::llround((x + 1.0) / kCell));
  const auto j = static_cast<std::uint64_t>(std::llround((y + 1.0) / kCell));
  std::uint64_t z = i * 1000003u + j + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
}

std::size_t labelled(const FlowRegions& r) { return r.ridge_vertices + r.valley_vertices; }

// Unbiased on noise alone; with a fifth of the values waves, at most 1.3× the noise.
TEST(RobustSpread, IsTheNoiseWhenSomeValuesAreWaves) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::uniform_real_distribution<double> wave(2.0, 10.0);
  std::vector<double> values(20000);
  for (double& value : values) value = noise(random);
  const std::vector<std::uint8_t> all(values.size(), 1);
  EXPECT_NEAR(robust_spread(values, all), 0.3, 0.015);
  for (std::size_t i = 0; i < values.size(); i += 5) values[i] = (i % 2 ? 1 : -1) * wave(random);
  EXPECT_GT(robust_spread(values, all), 0.3);
  EXPECT_LT(robust_spread(values, all), 1.3 * 0.3);
  std::vector<std::uint8_t> none(values.size(), 0);
  EXPECT_EQ(robust_spread(values, none), 0.0);
}

// The noise floor follows the jitter's amplitude, scales as H does (1/length), and a surface of
// smooth waves without jitter has almost none: its waves are not noise.
TEST(NoiseFloor, FollowsTheJitterAndNotTheWaves) {
  auto floor_of = [](double amplitude, double scale) {
    TriangleMesh m =
        tank(kGrid, [&](double x, double y) { return amplitude * kCell * jitter(x, y); });
    for (Vec3& p : m.positions) p *= scale;
    return flow_of(m).regions.noise_floor;
  };
  const double small = floor_of(0.05, 1.0), large = floor_of(0.2, 1.0);
  EXPECT_GT(small, 0.0);
  EXPECT_NEAR(large / small, 4.0, 0.4);
  EXPECT_NEAR(floor_of(0.2, 1000.0) * 1000.0 / large, 1.0, 1e-6);
  const Flow waves = flow_of(
      tank(kGrid, [](double x, double y) { return 0.05 * std::sin(6.0 * x) * std::cos(5.0 * y); }));
  double peak = 0.0;
  for (std::size_t v = 0; v < waves.regions.smoothed_field.size(); ++v)
    peak = std::max(peak, std::abs(waves.curvature.field.mean[v]));
  EXPECT_LT(waves.regions.noise_floor, 0.02 * peak);
  EXPECT_EQ(waves.regions.threshold, 2.0 / waves.regions.scale_length)
      << "the floor is not binding";
  EXPECT_GT(labelled(waves.regions), 0u);
}

// Calm water with marching-cubes-like jitter of up to 0.4 cells (vertex by vertex, rougher than
// marching cubes makes it): no flow at any amplitude, while a crest on realistic jitter (up to
// 0.1 cells) is drawn.
TEST(CalmWater, JitterIsNoFlowAndAWaveOnItIs) {
  for (const double amplitude : {0.05, 0.1, 0.2, 0.4}) {
    const Flow calm =
        flow_of(tank(kGrid, [&](double x, double y) { return amplitude * kCell * jitter(x, y); }));
    EXPECT_EQ(labelled(calm.regions), 0u) << "jitter of " << amplitude << " cells";
    if (amplitude > 0.1) continue;
    const HeightFunction crest = bump(0.1 + amplitude, 0.0, 0.0, 0.2);
    const Flow wave = flow_of(tank(
        kGrid, [&](double x, double y) { return amplitude * kCell * jitter(x, y) + crest(x, y); }));
    const std::size_t top = static_cast<std::size_t>(kGrid / 2) * kGrid + kGrid / 2;  // (0, 0)
    EXPECT_EQ(wave.regions.label[top], FlowLabel::ridge)
        << "jitter of " << amplitude << " cells: T " << wave.regions.threshold << ", noise floor "
        << wave.regions.noise_floor << ", s at the top " << wave.regions.field[top];
  }
}

// The surface of a tank droops into its walls over 3 cells: no region along them, and the shading
// normals there face up as the calm water's do; a crest running beside a wall 12 cells out is
// still drawn.
TEST(TankWalls, TheDroopAlongTheWallsIsCalmAndAWaveBesideThemIsNot) {
  auto to_wall = [](double x, double y) { return 1.0 - std::max(std::abs(x), std::abs(y)); };
  const auto droop = [&](double x, double y) {
    return -kCell * std::exp(-to_wall(x, y) / (3 * kCell));
  };
  const Flow calm = flow_of(tank(kGrid, droop));
  EXPECT_EQ(calm.regions.walls, 4u);
  EXPECT_EQ(labelled(calm.regions), 0u);
  // Tilted by less than 4.5° anywhere past the border ring, where the droop tilts by 18°.
  for (std::size_t v = 0; v < calm.curvature.mesh.positions.size(); ++v) {
    const Vec3& p = calm.curvature.mesh.positions[v];
    if (calm.regions.free_surface[v] && to_wall(p.x(), p.y()) > 2.5 * kCell) {
      EXPECT_GT(calm.regions.shading_normal[v].z(), 0.997) << p.transpose();
    }
  }
  // The same droop without the wall fade is a ridge all round (what the fade is for).
  FlowOptions no_noise_floor;
  no_noise_floor.threshold_relative = 2.0;
  const Flow open = flow_of(height_field(kGrid, droop), no_noise_floor);
  EXPECT_EQ(open.regions.walls, 0u);
  EXPECT_GT(open.regions.ridge_vertices, 0u);
  double open_tilt = 1.0;
  for (std::size_t v = 0; v < open.curvature.mesh.positions.size(); ++v) {
    const Vec3& p = open.curvature.mesh.positions[v];
    if (to_wall(p.x(), p.y()) > 2.5 * kCell)
      open_tilt = std::min(open_tilt, open.regions.shading_normal[v].z());
  }
  EXPECT_LT(open_tilt, 0.995);

  const Flow beside = flow_of(tank(kGrid, [&](double x, double y) {
    return droop(x, y) + 0.02 * std::exp(-std::pow((x - (-1.0 + 12 * kCell)) / (3 * kCell), 2));
  }));
  std::size_t along = 0;
  for (std::size_t v = 0; v < beside.curvature.mesh.positions.size(); ++v)
    along += beside.regions.label[v] == FlowLabel::ridge &&
             std::abs(beside.curvature.mesh.positions[v].x() - (-1.0 + 12 * kCell)) < 2 * kCell;
  EXPECT_GT(along, static_cast<std::size_t>(kGrid / 2));
}

TEST(TankWalls, AClosedTanksSidesAreWallsAndWeighNothingNearThem) {
  const TriangleMesh m = tank(21, [](double, double) { return 0.0; });
  const TankWalls walls = find_tank_walls(m, Axis::z, 0.1);
  EXPECT_EQ(walls.count(), 4u);
  const std::vector<double> weight = wall_weights(m, Axis::z, walls, 0.2, 0.4);
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const double d = 1.0 - std::max(std::abs(m.positions[v].x()), std::abs(m.positions[v].y()));
    if (d <= 0.2 + 1e-12) {
      EXPECT_EQ(weight[v], 0.0) << d;
    } else if (d >= 0.4 - 1e-12) {
      EXPECT_EQ(weight[v], 1.0) << d;
    } else if (d > 0.2 + 1e-9 && d < 0.4 - 1e-9) {
      EXPECT_TRUE(weight[v] > 0.0 && weight[v] < 1.0) << d;
    }
  }
  // A wave touching the side of its box over a short stretch makes no wall of it.
  TriangleMesh bulge = tank(21, [](double, double) { return 0.0; });
  for (Vec3& p : bulge.positions)
    if (p.x() > 0.99 && std::abs(p.y()) < 0.2) p.x() += 0.3;
  EXPECT_FALSE(find_tank_walls(bulge, Axis::z, 0.1).wall[1]);
}

// Twelve crests of growing height: at most max_regions are drawn, and they are the tallest.
TEST(Salience, OnlyTheMostSalientRegionsAreDrawn) {
  std::vector<HeightFunction> crests;
  for (int i = 0; i < 12; ++i)
    crests.push_back(bump(0.02 + 0.004 * i, -0.6 + 0.4 * (i % 4), -0.45 + 0.45 * (i / 4), 0.08));
  const Flow f = flow_of(tank(kGrid, [&](double x, double y) {
    double z = 0.0;
    for (const HeightFunction& c : crests) z += c(x, y);
    return z;
  }));
  const std::size_t limit = flow_defaults(FlowCriterion::mean).max_regions;
  ASSERT_EQ(limit, 6u);
  EXPECT_EQ(f.regions.regions, limit);
  for (int i = 0; i < 12; ++i) {
    const double x = -0.6 + 0.4 * (i % 4), y = -0.45 + 0.45 * (i / 4);
    const std::size_t v = static_cast<std::size_t>(std::lround((x + 1) / kCell)) * kGrid +
                          static_cast<std::size_t>(std::lround((y + 1) / kCell));
    EXPECT_EQ(f.regions.label[v] == FlowLabel::ridge, i >= 6) << "crest " << i;
  }
}

}  // namespace
}  // namespace toonwater::test
