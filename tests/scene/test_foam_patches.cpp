// Foam patches (scene/foam_patches.hpp): the foam's field from its particles, moved onto the
// water's surface, summed into few components without losing its shape, and left out where it
// cannot show.
#include "scene/foam_patches.hpp"

#include "scene/foam_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace toonwater {
namespace {

constexpr int kScreenWidth = 320, kScreenHeight = 180;

// A camera above and in front of the origin (POV-Ray's frame, y up), 40° wide.
ScreenProjection camera() {
  CameraPlacement c;
  c.location = Vec3(0, 2, -3);
  c.look_at = Vec3::Zero();
  c.angle = 40;
  return screen_projection(c, kScreenWidth, kScreenHeight);
}

// Flat water at y = `height` over [−1.5, 1.5]², `n` × `n` vertices, normals up.
SceneMesh flat_water(int n = 61, double height = 0.0) {
  SceneMesh m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.positions.emplace_back(-1.5 + 3.0 * i / (n - 1), height, -1.5 + 3.0 * j / (n - 1));
      m.normals.emplace_back(0, 1, 0);
    }
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n, d = c + 1;
      m.triangles.push_back({a, c, b});
      m.triangles.push_back({b, c, d});
    }
  m.min = Vec3(-1.5, height, -1.5);
  m.max = Vec3(1.5, height, 1.5);
  return m;
}

// `count` particles spread over a square `spread` wide around `centre`, at its height.
std::vector<Vec3> raft(const Vec3& centre, int count, double spread, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.5 * spread, 0.5 * spread);
  std::vector<Vec3> particles;
  for (int i = 0; i < count; ++i) particles.push_back(centre + Vec3(u(rng), 0, u(rng)));
  return particles;
}

double field_at(const std::vector<FoamComponent>& c, const Vec3& p) { return foam_field(c, p); }

TEST(FoamPatches, ACrowdOfParticlesMakesFoamAndASparseSpreadDoesNot) {
  const ScreenProjection s = camera();
  const SceneMesh water = flat_water();
  const FoamOptions options;
  const std::vector<Vec3> crowd = raft(Vec3(-0.5, 0, 0), 60, 0.05);
  const std::vector<FoamComponent> dense = foam_components(crowd, water, s, options);
  ASSERT_FALSE(dense.empty());
  EXPECT_GE(field_at(dense, Vec3(-0.5, 0, 0)), options.density);
  // Far from the crowd there is none.
  EXPECT_EQ(field_at(dense, Vec3(0.5, 0, 0)), 0.0);
  // The same number of particles spread over the whole pool: nowhere as many within a reach.
  const std::vector<FoamComponent> sparse =
      foam_components(raft(Vec3::Zero(), 60, 2.5), water, s, options);
  double most = 0.0;
  for (const FoamComponent& c : sparse) most = std::max(most, field_at(sparse, c.centre));
  EXPECT_LT(most, options.density);
}

TEST(FoamPatches, FoamJustUnderTheSurfaceIsMovedOntoItAndFoamFarFromItIsNone) {
  const ScreenProjection s = camera();
  const SceneMesh water = flat_water();
  const FoamOptions options;
  const double reach = options.reach_pixels * s.pixel_size(Vec3::Zero());
  // A simulator's foam a third of a reach under the surface: painted on it, as dense as on it.
  std::vector<Vec3> under = raft(Vec3(0.2, -reach / 3, 0.1), 60, 0.05);
  const std::vector<FoamComponent> moved = foam_components(under, water, s, options);
  ASSERT_FALSE(moved.empty());
  for (const FoamComponent& c : moved) EXPECT_NEAR(c.centre.y(), 0.0, 1e-12);
  EXPECT_GE(field_at(moved, Vec3(0.2, 0, 0.1)), options.density);
  // Bubbles deep down, or spray high above, are no foam on it.
  EXPECT_TRUE(
      foam_components(raft(Vec3(0.2, -5 * reach, 0.1), 60, 0.05), water, s, options).empty());
  EXPECT_TRUE(
      foam_components(raft(Vec3(0.2, 5 * reach, 0.1), 60, 0.05), water, s, options).empty());
}

TEST(FoamPatches, OnAMeshOfLargeFacesFoamStillLandsOnTheSurface) {
  const ScreenProjection s = camera();
  const SceneMesh coarse = flat_water(4, 0.1);  // faces a metre wide, 300 pixels on screen
  const FoamOptions options;
  const std::vector<FoamComponent> c =
      foam_components(raft(Vec3(0.3, 0.09, -0.2), 60, 0.05), coarse, s, options);
  ASSERT_FALSE(c.empty());
  for (const FoamComponent& f : c) EXPECT_NEAR(f.centre.y(), 0.1, 1e-12);
  EXPECT_GE(field_at(c, Vec3(0.3, 0.1, -0.2)), options.density);
}

TEST(FoamPatches, ParticlesThatCannotShowAreLeftOut) {
  const ScreenProjection s = camera();
  const SceneMesh water = flat_water(31, 0.0);
  const FoamOptions options;
  // Behind the camera, and far outside the picture to its side.
  std::vector<Vec3> hidden = raft(Vec3(0, 2, -5), 30, 0.05);
  const std::vector<Vec3> aside = raft(Vec3(40, 0, 0), 30, 0.05);
  hidden.insert(hidden.end(), aside.begin(), aside.end());
  EXPECT_TRUE(foam_components(hidden, water, s, options).empty());
  EXPECT_TRUE(foam_components(raft(Vec3::Zero(), 30, 0.05), SceneMesh{}, s, options).empty());
}

TEST(FoamPatches, ManyParticlesAreSummedIntoFewComponentsOfTheSameField) {
  const ScreenProjection s = camera();
  const SceneMesh water = flat_water(121);
  FoamOptions options;
  const std::vector<Vec3> many = raft(Vec3::Zero(), 200000, 2.0, 7);
  const std::vector<FoamComponent> summed = foam_components(many, water, s, options);
  ASSERT_FALSE(summed.empty());
  EXPECT_LE(summed.size(), kMaxFoamComponents);
  double total = 0.0;
  for (const FoamComponent& c : summed) total += c.strength * std::pow(c.radius, 3);
  double particles = 0.0;  // every particle's foam counted once: S·R³ summed
  for (const Vec3& p : many) particles += std::pow(options.reach_pixels * s.pixel_size(p), 3);
  EXPECT_NEAR(total, particles, 1e-4 * particles);
  // Against each particle as its own component, where the field is about a patch's edge (some
  // six particles within a reach): it differs by a tenth of that at most.
  std::vector<Vec3> few = raft(Vec3::Zero(), 3000, 2.0, 7);
  const std::vector<FoamComponent> coarse = foam_components(few, water, s, options);
  std::vector<FoamComponent> exact;
  for (const Vec3& p : few) exact.push_back({p, options.reach_pixels * s.pixel_size(p), 1.0});
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  double worst = 0.0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 p(u(rng), 0, u(rng));
    worst = std::max(worst, std::abs(field_at(coarse, p) - field_at(exact, p)));
  }
  EXPECT_LT(worst, 0.1 * options.density) << "the summed field strays from the particles' own";
}

TEST(FoamPatches, TheIncludeDeclaresABlobOnlyWhenThereIsFoam) {
  EXPECT_EQ(foam_include({}, 6.0).find("Foam_patches"), std::string::npos);
  const std::vector<FoamComponent> one{{Vec3(1, 2, 3), 0.5, 7}};
  const std::string text = foam_include(one, 6.0);
  EXPECT_NE(text.find("#declare Foam_patches = blob {"), std::string::npos) << text;
  EXPECT_NE(text.find("threshold 6"), std::string::npos) << text;
  EXPECT_NE(text.find("sphere { <1,2,3>, 0.5, 7 }"), std::string::npos) << text;
}

}  // namespace
}  // namespace toonwater
