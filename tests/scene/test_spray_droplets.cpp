// Spray droplets (scene/spray_droplets.hpp): clouds of particles gathered on screen into a few
// droplets sized in pixels, spray under the water left out, and droplets carried from frame to
// frame: matched, grown in, stretched along their motion, faded out.
#include "scene/spray_droplets.hpp"

#include "scene/droplet_writer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace toonwater {
namespace {

constexpr int kWidth = 320, kHeight = 180;

// A camera on −z looking along +z (POV-Ray's frame) at the origin, 40° wide.
CameraPlacement front_camera() {
  CameraPlacement c;
  c.location = Vec3(0, 0, -4);
  c.look_at = Vec3::Zero();
  c.angle = 40;
  return c;
}

// `count` particles within `spread` of `centre`.
void add_cloud(std::vector<Vec3>& particles, const Vec3& centre, int count, double spread,
               unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-spread, spread);
  for (int i = 0; i < count; ++i) particles.push_back(centre + Vec3(u(rng), u(rng), u(rng)));
}

Eigen::Vector2d pixel_of(const ScreenProjection& s, const Vec3& p) { return *s.pixel(p); }

TEST(SprayDroplets, TheProjectionIsScenePovsCamera) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  // The look_at point at the centre; +x to the right, +y up; the edge of a 40° view at x = 4 tan
  // 20°.
  EXPECT_NEAR((pixel_of(s, Vec3::Zero()) - Eigen::Vector2d(160, 90)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(pixel_of(s, Vec3(4 * std::tan(20 * M_PI / 180), 0, 0)).x(), kWidth, 1e-9);
  EXPECT_LT(pixel_of(s, Vec3(0, 0.5, 0)).y(), 90);
  EXPECT_FALSE(s.pixel(Vec3(0, 0, -5)));  // behind the camera
}

TEST(SprayDroplets, EachCloudIsOneDropletAtItsMeanAndALoneParticleIsNone) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  std::vector<Vec3> spray;
  add_cloud(spray, Vec3(-0.8, 0.3, 0), 30, 0.01, 1);
  add_cloud(spray, Vec3(0.7, -0.2, 0.5), 12, 0.01, 2);
  spray.push_back(Vec3(0.0, 0.6, 0));  // a stray particle
  DropletOptions options;
  const std::vector<Droplet> d = spray_droplets(spray, s, options);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0].particles, 30u);  // most particles first
  EXPECT_EQ(d[1].particles, 12u);
  EXPECT_LT((d[0].centre - Vec3(-0.8, 0.3, 0)).norm(), 0.01);
  EXPECT_LT((d[1].centre - Vec3(0.7, -0.2, 0.5)).norm(), 0.01);
  // Sized in pixels: the smaller (median) droplet is size_pixels across, the denser one more
  // (the square root of its count over the median's: sqrt(2.5)), and both round.
  EXPECT_NEAR(2 * d[1].radius / s.pixel_size(d[1].centre), options.size_pixels, 1e-9);
  EXPECT_NEAR(2 * d[0].radius / s.pixel_size(d[0].centre),
              options.size_pixels * std::sqrt(30.0 / 12.0), 1e-9);
  EXPECT_EQ(d[0].tail, d[0].centre);
}

TEST(SprayDroplets, ADenserSimulationGivesTheSameDroplets) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  std::vector<Vec3> coarse, fine;
  for (int c = 0; c < 5; ++c) {
    const Vec3 centre(-1.0 + 0.5 * c, 0.2 * c - 0.4, 0.1 * c);
    add_cloud(coarse, centre, 10, 0.01, 10 + c);
    add_cloud(fine, centre, 80, 0.01, 20 + c);
  }
  const std::vector<Droplet> a = spray_droplets(coarse, s, {}), b = spray_droplets(fine, s, {});
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(b.size(), 5u);
  for (const Droplet& da : a) {
    double nearest = 1e9;
    for (const Droplet& db : b) nearest = std::min(nearest, (da.centre - db.centre).norm());
    EXPECT_LT(nearest, 0.01);
  }
}

TEST(SprayDroplets, AFrameShowsItsMostSalientDropletsOnly) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  std::vector<Vec3> spray;
  for (int c = 0; c < 30; ++c)  // 30 clouds on a 6 × 5 lattice, cloud c of 2 + c particles
    add_cloud(spray, Vec3(-1.0 + 0.4 * (c % 6), -0.6 + 0.3 * (c / 6), 0), 2 + c, 0.005, 100 + c);
  DropletOptions options;
  options.max_droplets = 7;
  const std::vector<Droplet> d = spray_droplets(spray, s, options);
  ASSERT_EQ(d.size(), 7u);
  for (std::size_t i = 0; i < d.size(); ++i) EXPECT_EQ(d[i].particles, 31u - i);
}

TEST(SprayDroplets, ADropletExpectedThereKeepsItsPlaceAgainstANewOneOfUpToTwiceItsParticles) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  // Three clouds, far apart: 25 particles where a droplet is expected, new ones of 40 and 30.
  const Vec3 tracked(-1, 0, 0), bigger(0, 0, 0), equal(1, 0, 0);
  std::vector<Vec3> spray;
  add_cloud(spray, tracked, 25, 0.005, 1);
  add_cloud(spray, bigger, 40, 0.005, 2);
  add_cloud(spray, equal, 30, 0.005, 3);
  DropletOptions options;
  options.max_droplets = 2;
  // By count alone the two new ones are drawn; expected, the tracked one outranks the one of 30
  // (under twice its particles), not the one of 40 (over twice).
  const std::vector<Droplet> by_count = spray_droplets(spray, s, options);
  ASSERT_EQ(by_count.size(), 2u);
  EXPECT_EQ(by_count[0].particles, 40u);
  EXPECT_EQ(by_count[1].particles, 30u);
  const std::vector<Vec3> expected{tracked};
  const std::vector<Droplet> kept = spray_droplets(spray, s, options, nullptr, expected);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].particles, 40u);
  EXPECT_EQ(kept[1].particles, 25u);
  EXPECT_EQ(kept[1].gathered_at, 0);
  EXPECT_EQ(kept[0].gathered_at, -1);
}

TEST(SprayDroplets, ADropletExpectedWhereItsParticlesAreIsGatheredBeforeAFullerNeighbour) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  // The point at pixel column px on the image's middle row, at the look_at's depth.
  const auto at_column = [](double px) {
    return Vec3((px - 0.5 * kWidth) * 4.0 * std::tan(20 * M_PI / 180) / (0.5 * kWidth), 0, 0);
  };
  // A droplet's particles astride two cells of the 16-pixel grid (columns 157.5 and 162.5), and
  // a fuller cloud in the next cell but one (column 178.5), whose 3 × 3 block reaches A's right
  // half.
  std::vector<Vec3> spray;
  add_cloud(spray, at_column(157.5), 6, 1e-4, 1);
  add_cloud(spray, at_column(162.5), 6, 1e-4, 2);
  add_cloud(spray, at_column(178.5), 30, 1e-4, 3);
  const DropletOptions options;
  // Alone, the fuller cloud is gathered first and takes half of the other.
  const std::vector<Droplet> split = spray_droplets(spray, s, options);
  ASSERT_EQ(split.size(), 2u);
  EXPECT_EQ(split[0].particles, 36u);
  EXPECT_EQ(split[1].particles, 6u);
  // Expected where its left half is, the droplet is gathered whole first.
  const std::vector<Vec3> expected{at_column(157.5)};
  const std::vector<Droplet> whole = spray_droplets(spray, s, options, nullptr, expected);
  ASSERT_EQ(whole.size(), 2u);
  EXPECT_EQ(whole[0].particles, 30u);
  EXPECT_EQ(whole[1].particles, 12u);
  EXPECT_NEAR(pixel_of(s, whole[1].centre).x(), 160.0, 0.1);
}

TEST(SprayDroplets, OnceDropletsAreFoundAgainANewOnesVelocityTellsWhereToLookForIt) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  DropletTracks tracks;
  const DropletOptions options;
  // Each frame a new droplet is thrown whose particles carry the velocity v, in units the
  // simulation chose: it moves 0.04·v a frame. The older ones fly on the same way.
  const Vec3 v(2.0, 1.0, 0.0);
  constexpr double scale = 0.04;
  std::vector<Vec3> thrown;
  for (int frame = 0; frame < 6; ++frame) {
    for (Vec3& p : thrown) p += scale * v;
    thrown.push_back(Vec3(-1.3 + 0.45 * frame, -0.5, 0.0));  // 50 pixels right of the last
    std::vector<Vec3> spray, velocities;
    for (std::size_t i = 0; i < thrown.size(); ++i)
      add_cloud(spray, thrown[i], 10, 0.002, static_cast<unsigned>(7 + i));
    velocities.assign(spray.size(), v);
    tracks.update(spray_droplets(spray, s, options, nullptr, tracks.predicted(), velocities), s,
                  options);
  }
  // The newest droplet, found once, is expected where its velocity takes it at the fitted scale.
  const std::vector<Vec3> expected = tracks.predicted();
  const Vec3 newest = thrown.back() + scale * v;
  const auto nearest = std::min_element(
      expected.begin(), expected.end(),
      [&](const Vec3& a, const Vec3& b) { return (a - newest).norm() < (b - newest).norm(); });
  ASSERT_NE(nearest, expected.end());
  EXPECT_LT((*nearest - newest).norm(), 1e-3);
}

TEST(SprayDroplets, AFallingDropletIsExpectedWhereItsParticlesVelocityTakesIt) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  DropletTracks tracks;
  const DropletOptions options;
  // Eight droplets drift at a steady velocity (the scale's calibration: 0.04 a frame per unit
  // of velocity); one more is thrown up and falls back, its particles' velocity changing by
  // 5 units a frame, so that its last motion misses its next place by 0.2 (22 pixels, beyond
  // the spacing of 16 within which a moving droplet is matched), while its velocity takes it
  // there.
  constexpr double scale = 0.04;
  const Vec3 drift(1.0, 0.0, 0.0), gravity(0.0, -5.0, 0.0);
  std::vector<Vec3> drifting;
  for (int i = 0; i < 8; ++i)
    drifting.push_back(Vec3(-1.6 + 0.4 * (i % 4), 0.5 + 0.3 * (i / 4), 0));
  Vec3 falling(0.4, -0.6, 0), velocity(0.0, 12.0, 0.0);
  int carried = 0;
  for (int frame = 0; frame < 8; ++frame) {
    std::vector<Vec3> spray, velocities;
    for (std::size_t i = 0; i < drifting.size(); ++i) {
      add_cloud(spray, drifting[i], 20, 0.004, static_cast<unsigned>(10 + i));
      velocities.resize(spray.size(), drift);
    }
    add_cloud(spray, falling, 20, 0.004, 99);
    velocities.resize(spray.size(), velocity);
    const std::vector<Vec3> expected = tracks.predicted();
    if (frame >= 3) {  // calibrated: the falling droplet is expected exactly where it is
      ASSERT_FALSE(expected.empty());
      const auto nearest =
          std::min_element(expected.begin(), expected.end(), [&](const Vec3& a, const Vec3& b) {
            return (a - falling).norm() < (b - falling).norm();
          });
      EXPECT_LT((*nearest - falling).norm(), 0.004) << frame;
    }
    const std::vector<Droplet> drawn =
        tracks.update(spray_droplets(spray, s, options, nullptr, expected, velocities), s, options);
    for (const Droplet& d : drawn)
      if (!d.fading && (d.centre - falling).norm() < 0.01 && d.age > 0) ++carried;
    for (Vec3& p : drifting) p += scale * drift;
    falling += scale * velocity;
    velocity += gravity;
  }
  // Found again in every frame once the scale is known (from the third on): in the second, a
  // droplet seen once and not yet expected anywhere is looked for within three spacings only.
  EXPECT_EQ(carried, 6);
}

TEST(SprayDroplets, SprayUnderTheWaterIsLeftOut) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  // A closed box of water, y from −1 to 0, and an open sheet at y = 0 beside it.
  SceneMesh box;
  box.positions = {{-1, -1, -1}, {0, -1, -1}, {0, 0, -1}, {-1, 0, -1},
                   {-1, -1, 1},  {0, -1, 1},  {0, 0, 1},  {-1, 0, 1}};
  box.triangles = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                   {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
  const int sheet = static_cast<int>(box.positions.size());
  for (const Vec3& p : {Vec3(0.1, 0, -1), Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(0.1, 0, 1)})
    box.positions.push_back(p);
  box.triangles.push_back({sheet, sheet + 2, sheet + 1});
  box.triangles.push_back({sheet, sheet + 3, sheet + 2});
  box.min = Vec3(-1, -1, -1);
  box.max = Vec3(1, 0, 1);
  std::vector<Vec3> spray;
  const std::vector<Vec3> under{{-0.5, -0.4, 0.2}, {0.5, -0.2, 0.3}},
      over{{-0.5, 0.3, 0.2}, {0.5, 0.2, 0.3}};
  for (const Vec3& c : under) add_cloud(spray, c, 20, 0.01, 7);
  for (const Vec3& c : over) add_cloud(spray, c, 10, 0.01, 8);
  const std::vector<Droplet> d = spray_droplets(spray, s, {}, &box);
  ASSERT_EQ(d.size(), 2u);
  for (const Droplet& droplet : d) EXPECT_GT(droplet.centre.y(), 0.0);
  EXPECT_EQ(spray_droplets(spray, s, {}).size(), 4u);
  // Bubbles are the other way round.
  DropletOptions bubbles;
  bubbles.under_water = true;
  const std::vector<Droplet> b = spray_droplets(spray, s, bubbles, &box);
  ASSERT_EQ(b.size(), 2u);
  for (const Droplet& bubble : b) EXPECT_LT(bubble.centre.y(), 0.0);

  // Spray skimming just under the surface (a tenth of a droplet size: 0.0073 here): a new
  // droplet there is left out, one found where it was expected is kept; deeper than two
  // droplet sizes, neither.
  const double size = DropletOptions{}.size_pixels * s.pixel_size(Vec3(0.5, 0, 0.3));
  std::vector<Vec3> skimming, deep;
  add_cloud(skimming, Vec3(0.5, -0.1 * size, 0.3), 20, 0.001, 9);
  add_cloud(deep, Vec3(0.5, -3 * size, 0.3), 20, 0.001, 9);
  const std::vector<Vec3> expected{Vec3(0.5, -0.1 * size, 0.3)};
  EXPECT_TRUE(spray_droplets(skimming, s, {}, &box).empty());
  EXPECT_EQ(spray_droplets(skimming, s, {}, &box, expected).size(), 1u);
  const std::vector<Vec3> expected_deep{Vec3(0.5, -3 * size, 0.3)};
  EXPECT_TRUE(spray_droplets(deep, s, {}, &box, expected_deep).empty());
}

TEST(SprayDroplets, ADropletIsCarriedGrownStretchedAndFaded) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  DropletTracks tracks;
  const DropletOptions options;
  auto frame = [&](const std::vector<Vec3>& centres) {
    std::vector<Vec3> spray;
    for (std::size_t i = 0; i < centres.size(); ++i) add_cloud(spray, centres[i], 20, 0.005, 3);
    return tracks.update(spray_droplets(spray, s, options), s, options);
  };
  // Frame 1: as found. Frame 2: a second droplet is born small; the first moves slowly.
  const Vec3 a(0, 0, 0), b(0.8, 0.3, 0);
  const std::vector<Droplet> f1 = frame({a});
  ASSERT_EQ(f1.size(), 1u);
  const double full = f1[0].radius;
  const std::vector<Droplet> f2 = frame({a + Vec3(0.01, 0, 0), b});
  ASSERT_EQ(f2.size(), 2u);
  const Droplet& born = f2[0].centre.x() > 0.5 ? f2[0] : f2[1];
  const Droplet& slow = f2[0].centre.x() > 0.5 ? f2[1] : f2[0];
  EXPECT_NEAR(born.radius / full, 0.5, 0.05);
  EXPECT_EQ(born.age, 0);
  EXPECT_GT(slow.age, 0);
  EXPECT_EQ(slow.tail, slow.centre);  // moved less than its radius: round
  // Only the droplet whose motion is known is expected somewhere: one more step on.
  const std::vector<Vec3> expected = tracks.predicted();
  ASSERT_EQ(expected.size(), 1u);
  EXPECT_NEAR((expected[0] - (slow.centre + (slow.centre - f1[0].centre))).norm(), 0.0, 1e-12);
  // Frame 3: the first droplet jumps by three of its radii: a teardrop whose tail points back.
  const Vec3 jump(3 * full, 0, 0);
  const std::vector<Droplet> f3 = frame({a + Vec3(0.01, 0, 0) + jump, b});
  ASSERT_EQ(f3.size(), 2u);
  const Droplet& fast = f3[0].centre.x() < 0.5 ? f3[0] : f3[1];
  const Vec3 tail = fast.tail - fast.centre;
  EXPECT_GT(tail.norm(), fast.radius);
  EXPECT_LE(tail.norm(), 3 * fast.radius + 1e-12);
  EXPECT_LT(tail.normalized().dot(jump.normalized()), -0.999);
  const Droplet& growing = f3[0].centre.x() < 0.5 ? f3[1] : f3[0];
  EXPECT_NEAR(growing.radius / full, 0.75, 0.05);
  // Frame 4: the first droplet's particles are gone: it is drawn once more where it would be,
  // smaller; frame 5: gone.
  const std::vector<Droplet> f4 = frame({b});
  ASSERT_EQ(f4.size(), 2u);
  const Droplet& fading = f4[0].centre.x() < 0.5 ? f4[0] : f4[1];
  EXPECT_TRUE(fading.fading);
  EXPECT_LT(fading.radius, 0.6 * full);
  EXPECT_GT(fading.centre.x(), fast.centre.x());
  EXPECT_EQ(frame({b}).size(), 1u);
}

TEST(SprayDroplets, TheIncludeOutlinesEachDropletInPixels) {
  const ScreenProjection s = screen_projection(front_camera(), kWidth, kHeight);
  Droplet d;
  d.centre = d.tail = Vec3(0, 0, 2);
  d.radius = 0.05;
  const std::string text = spray_include(std::vector<Droplet>{d}, s, LightGeometry{}, 2.0);
  EXPECT_NE(text.find("#declare Spray_droplets = union {"), std::string::npos);
  // A 2-pixel line at distance 6: 2 · 6 / focal.
  char expected[64];
  std::snprintf(expected, sizeof expected, ", %.7g, <0,1,0>)", 2.0 * 6.0 / s.focal_pixels);
  EXPECT_NE(text.find(expected), std::string::npos) << text;
  EXPECT_EQ(spray_include({}, s, LightGeometry{}, 2.0).find("Toon_droplet("), std::string::npos);
}

}  // namespace
}  // namespace toonwater
