// Spray and foam drawn as a cartoon draws them (issue 33): povgen --particles, rendered with
// POV-Ray and read back, and the droplets and foam of the shared dam break from frame to frame.
#include "tests/support/povray_test_util.hpp"

#include "analyzer/affine_transform.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/particles.hpp"
#include "scene/axes.hpp"
#include "scene/spray_droplets.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr int kPictureWidth = 320, kPictureHeight = 180;
// The camera (y-up input): on +z, level with y = 0.5, looking along −z.
const Vec3 kCamera(0, 0.5, 4), kLookAt(0, 0.5, 0);
constexpr double kAngle = 40;

// Where a point of the input lands in the picture (a right-handed pinhole: +x right, +y up).
std::array<double, 2> project(const Vec3& p) {
  const double focal = 0.5 * kPictureWidth / std::tan(0.5 * kAngle * std::numbers::pi / 180.0);
  const double depth = kCamera.z() - p.z();
  return {0.5 * kPictureWidth + focal * (p.x() - kCamera.x()) / depth,
          0.5 * kPictureHeight - focal * (p.y() - kCamera.y()) / depth};
}

std::vector<std::pair<int, Vec3>> cloud(const Vec3& centre, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.01, 0.01);
  std::vector<std::pair<int, Vec3>> particles;
  for (int i = 0; i < count; ++i)
    particles.emplace_back(i % 256, centre + Vec3(u(rng), u(rng), u(rng)));
  return particles;
}

// povgen on a flat pool (y = 0 over [−1.5, 1.5]²), with the given extra arguments, rendered
// without antialiasing.
Image render_pool(const ScratchDir& dir, const std::vector<std::string>& extra) {
  write_obj(dir / "water.obj", make_height_grid(8, 1.5, [](double, double) { return 0.0; }));
  std::vector<std::string> args{"povgen",
                                "--water",
                                (dir / "water.obj").string(),
                                "--out",
                                (dir / "scene").string(),
                                "--set",
                                "render.antialias=false",
                                "--set",
                                "render.width=" + std::to_string(kPictureWidth),
                                "--set",
                                "render.height=" + std::to_string(kPictureHeight),
                                "--set",
                                "camera.location=[0, 0.5, 4]",
                                "--set",
                                "camera.look_at=[0, 0.5, 0]",
                                "--set",
                                "camera.angle=40"};
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult r = run_toonwater(args);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const Povray p = run_povray(dir / "scene");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  return read_image(dir / "scene" / "frame.png");
}

bool is_line(const Rgb8& c) { return std::max({c[0], c[1], c[2]}) < 60; }

// The pixel at (x, y), or the background's colour outside the picture.
Rgb8 pixel(const Image& image, double x, double y) {
  const long px = std::lround(x), py = std::lround(y);
  if (px < 0 || py < 0 || px >= image.width || py >= image.height) return to_rgb8(0.93, 0.96, 1);
  return image.at(static_cast<int>(px), static_cast<int>(py));
}

TEST(SprayRender, DropletsInTheAirAreOutlinedAndSprayUnderTheWaterIsNot) {
  ScratchDir dir;
  const std::vector<Vec3> in_air{{-0.8, 1.0, 0}, {0.0, 1.1, 0}, {0.8, 0.9, 0}};
  std::vector<std::pair<int, Vec3>> spray;
  for (std::size_t c = 0; c < in_air.size(); ++c) {
    const auto more = cloud(in_air[c], 12 + 4 * static_cast<int>(c), static_cast<unsigned>(10 + c));
    spray.insert(spray.end(), more.begin(), more.end());
  }
  const auto under = cloud({0.4, -0.3, 0.5}, 40, 99);  // the most particles, under the water
  spray.insert(spray.end(), under.begin(), under.end());
  write_text(dir / "spray000001.wwp", wwp_bytes(spray));
  const Image image = render_pool(dir, {"--particles", (dir / "spray000001.wwp").string()});
  ASSERT_EQ(image.width, kPictureWidth);
  ASSERT_EQ(image.height, kPictureHeight);
  const std::string include = read_text(dir / "scene" / "spray_0000.inc");
  std::size_t drawn = 0;
  for (std::size_t at = include.find("Toon_droplet("); at != std::string::npos;
       at = include.find("Toon_droplet(", at + 1))
    ++drawn;
  EXPECT_EQ(drawn, 3u) << include;

  const Rgb8 background = to_rgb8(0.93, 0.96, 1.0);
  for (const Vec3& c : in_air) {
    const auto [cx, cy] = project(c);
    const Rgb8 inside = pixel(image, cx, cy);
    EXPECT_FALSE(near(inside, background, 8)) << "no droplet at " << cx << ", " << cy;
    EXPECT_FALSE(is_line(inside)) << "a droplet's body is not its line";
    // Its silhouette, a disc of 4 to 5.7 pixels' radius (8 pixels across at the median, up to
    // sqrt(2) times that for the densest of the three): a line all round it, 2 pixels wide.
    // Each ray out from the centre must cross line pixels before the background.
    int rays = 0, outlined = 0;
    for (int a = 0; a < 72; ++a, ++rays) {
      const double angle = a * std::numbers::pi / 36.0;
      for (double r = 1.0; r < 12.0; r += 0.5) {
        const Rgb8 p = pixel(image, cx + r * std::cos(angle), cy + r * std::sin(angle));
        if (is_line(p)) {
          ++outlined;
          break;
        }
        if (near(p, background, 8)) break;
      }
    }
    EXPECT_GE(outlined, 0.9 * rays) << "outline around " << outlined << " of " << rays << " rays";
  }
  // Under the water at (0.4, −0.3, 0.5) nothing of a droplet shows through.
  const auto [ux, uy] = project({0.4, -0.3, 0.5});
  for (int dy = -4; dy <= 4; ++dy)
    for (int dx = -4; dx <= 4; ++dx) EXPECT_FALSE(is_line(pixel(image, ux + dx, uy + dy)));
}

TEST(SprayRender, ASceneWithoutParticlesHoldsNoneOfTheirMacros) {
  ScratchDir dir;
  render_pool(dir, {});
  const std::string toon = read_text(dir / "scene" / "toon.inc");
  EXPECT_EQ(toon.find("Toon_droplet"), std::string::npos);
  EXPECT_EQ(toon.find("Toon_foam"), std::string::npos);
  EXPECT_EQ(toon.find("Toon_bubble"), std::string::npos);
  EXPECT_EQ(read_text(dir / "scene" / "scene.pov").find("Spray"), std::string::npos);
  EXPECT_EQ(read_text(dir / "scene" / "scene.pov").find("Foam"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "scene" / "spray_0000.inc"));
  EXPECT_FALSE(fs::exists(dir / "scene" / "foam_0000.inc"));
  EXPECT_FALSE(fs::exists(dir / "scene" / "bubbles_0000.inc"));
}

// The line pixels in the square of half-width `radius` around (x, y).
int line_pixels_near(const Image& image, double x, double y, int radius) {
  int count = 0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx)
      count += is_line(pixel(image, x + dx, y + dy)) ? 1 : 0;
  return count;
}

TEST(BubbleRender, BubblesUnderTheWaterAreOutlinedDiscsSeenThroughItAndNoneInTheAir) {
  // Clouds of bubbles under the pool's surface, seen from above, and one in the air (not a
  // bubble there).
  const std::vector<Vec3> under{{-0.6, -0.05, 0.0}, {0.0, -0.05, 0.0}, {0.6, -0.05, 0.0}};
  std::vector<std::pair<int, Vec3>> bubbles;
  for (std::size_t c = 0; c < under.size(); ++c) {
    const auto more = cloud(under[c], 20, static_cast<unsigned>(20 + c));
    bubbles.insert(bubbles.end(), more.begin(), more.end());
  }
  const auto in_air = cloud({0.0, 0.8, 0.0}, 30, 40);
  bubbles.insert(bubbles.end(), in_air.begin(), in_air.end());
  const std::vector<std::string> above{"--set", "camera.location=[0, 2.5, 2.5]", "--set",
                                       "camera.look_at=[0, 0, 0]"};
  ScratchDir with, without;
  write_text(with / "bubble000001.wwp", wwp_bytes(bubbles));
  write_text(without / "bubble000001.wwp", wwp_bytes(bubbles));
  std::vector<std::string> args{"--particles", (with / "bubble000001.wwp").string()};
  args.insert(args.end(), above.begin(), above.end());
  const Image drawn = render_pool(with, args);
  args = {"--particles", (without / "bubble000001.wwp").string(), "--set",
          "particles.bubbles=false"};
  args.insert(args.end(), above.begin(), above.end());
  const Image plain = render_pool(without, args);
  const std::string include = read_text(with / "scene" / "bubbles_0000.inc");
  std::size_t count = 0;
  for (std::size_t at = include.find("Toon_bubble("); at != std::string::npos;
       at = include.find("Toon_bubble(", at + 1))
    ++count;
  EXPECT_EQ(count, 3u) << include;  // the three under the water, not the one in the air
  EXPECT_FALSE(fs::exists(without / "scene" / "bubbles_0000.inc"));
  // Each shows, bent a little by the surface, as a ring of line pixels where the same scene
  // without bubbles has none. The input is y-up, so POV-Ray's frame flips z.
  CameraPlacement camera;
  camera.location = Vec3(0, 2.5, -2.5);
  camera.look_at = Vec3::Zero();
  camera.angle = 40;
  const ScreenProjection screen = screen_projection(camera, kPictureWidth, kPictureHeight);
  for (const Vec3& c : under) {
    const Eigen::Vector2d at = *screen.pixel(Vec3(c.x(), c.y(), -c.z()));
    EXPECT_EQ(line_pixels_near(plain, at.x(), at.y(), 12), 0);
    EXPECT_GE(line_pixels_near(drawn, at.x(), at.y(), 12), 12)
        << "no bubble's line near " << at.x() << ", " << at.y();
  }
  const Eigen::Vector2d air = *screen.pixel(Vec3(0.0, 0.8, 0.0));
  EXPECT_EQ(line_pixels_near(drawn, air.x(), air.y(), 12), 0) << "a bubble in the air";
}

// Foam in a colour nothing else in the picture has.
const std::vector<std::string> kMagentaFoam{"--set", "particles.foam_color=[1, 0, 1]"};
bool is_foam(const Rgb8& c) { return c[0] > 200 && c[1] < 60 && c[2] > 200; }

// The foam pixels within `radius` pixels of (x, y).
int foam_pixels_near(const Image& image, double x, double y, int radius) {
  int count = 0;
  for (int dy = -radius; dy <= radius; ++dy)
    for (int dx = -radius; dx <= radius; ++dx)
      count += is_foam(pixel(image, x + dx, y + dy)) ? 1 : 0;
  return count;
}

TEST(FoamRender, FoamGatheredAtTheSurfaceIsAPatchOnItAndSparseOrDeepFoamIsNone) {
  ScratchDir dir;
  // A raft of foam a few millimetres under the surface, as simulators keep it; a sparse spread
  // on it; a crowd deep under it.
  std::vector<std::pair<int, Vec3>> foam = cloud({-0.5, -0.004, 1.0}, 80, 1);
  for (int i = 0; i < 6; ++i) foam.emplace_back(0, Vec3(0.2 + 0.15 * i, 0.0, 1.0));
  const auto deep = cloud({0.5, -0.6, 0.5}, 80, 2);
  foam.insert(foam.end(), deep.begin(), deep.end());
  write_text(dir / "foam000001.wwp", wwp_bytes(foam));
  std::vector<std::string> args{"--particles", (dir / "foam000001.wwp").string()};
  args.insert(args.end(), kMagentaFoam.begin(), kMagentaFoam.end());
  const Image image = render_pool(dir, args);
  ASSERT_EQ(image.width, kPictureWidth);
  // The raft: a patch several pixels across, flat in the foam's colour, on the water.
  const auto [fx, fy] = project({-0.5, 0.0, 1.0});
  EXPECT_TRUE(is_foam(pixel(image, fx, fy))) << fx << ", " << fy;
  EXPECT_GE(foam_pixels_near(image, fx, fy, 8), 12);
  // Nothing of the sparse or the deep foam, and nothing elsewhere: every foam pixel is the raft's.
  int total = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) total += is_foam(image.at(x, y)) ? 1 : 0;
  EXPECT_EQ(total, foam_pixels_near(image, fx, fy, 20));
  for (int i = 0; i < 6; ++i) {
    const auto [sx, sy] = project({0.2 + 0.15 * i, 0.0, 1.0});
    EXPECT_EQ(foam_pixels_near(image, sx, sy, 4), 0) << "a lone particle makes no patch";
  }
  // Off: no foam include, no foam in the picture.
  ScratchDir off;
  write_text(off / "foam000001.wwp", wwp_bytes(foam));
  std::vector<std::string> without{"--particles", (off / "foam000001.wwp").string(), "--set",
                                   "particles.foam=false"};
  without.insert(without.end(), kMagentaFoam.begin(), kMagentaFoam.end());
  const Image plain = render_pool(off, without);
  EXPECT_FALSE(is_foam(pixel(plain, fx, fy)));
  EXPECT_FALSE(fs::exists(off / "scene" / "foam_0000.inc"));
}

TEST(SprayRender, AParticleCacheMissingAFrameIsRefusedNamingIt) {
  ScratchDir dir;
  for (int f = 1; f <= 3; ++f)
    write_obj(dir / ("water_000" + std::to_string(f) + ".obj"),
              make_height_grid(4, 1.0, [](double, double) { return 0.0; }));
  for (int f : {1, 3})
    write_text(dir / ("spray00000" + std::to_string(f) + ".wwp"), wwp_bytes({{0, {0, 1, 0}}}));
  const CommandResult r =
      run_toonwater({"povgen", "--water", (dir / "water_####.obj").string(), "--particles",
                     (dir / "spray######.wwp").string(), "--out", (dir / "scene").string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find("spray######.wwp: the particles have no file for frame 2"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir / "scene"));
  write_text(dir / "spray000002.wwp", wwp_bytes({{0, {0, 1e30, 0}}}));
  const CommandResult far =
      run_toonwater({"povgen", "--water", (dir / "water_####.obj").string(), "--particles",
                     (dir / "spray######.wwp").string(), "--out", (dir / "scene").string()});
  EXPECT_EQ(far.exit_code, 2) << far.output;
  EXPECT_NE(far.output.find("spray000002.wwp: particle 0 lies beyond"), std::string::npos)
      << far.output;
  EXPECT_FALSE(fs::exists(dir / "scene"));
  const CommandResult missing =
      run_toonwater({"povgen", "--water", (dir / "water_####.obj").string(), "--particles",
                     (dir / "foam_####.vdb").string(), "--out", (dir / "scene").string()});
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  EXPECT_NE(missing.output.find("foam_####.vdb"), std::string::npos) << missing.output;
}

// The dam break's spray, frames 14–24 (the crown, its droplets and their fall), as povgen places
// it: the mesh cache and the particle cache mapped by the same --scale 1.2 --translate 0,0,0.3,
// Z up, the default camera on the water of those frames at 640×360.
TEST(SprayRender, TheDamBreaksDropletsAreFewAndCarriedFromFrameToFrame) {
  const fs::path data = shared_dir().empty() ? fs::path() : shared_dir() / "data";
  const fs::path bake = data / "mantaflow-dambreak" / "cache";
  if (data.empty() || !fs::exists(bake / "particles"))
    GTEST_SKIP() << "../shared/data/mantaflow-dambreak is absent: real-data test skipped";
  const AffineTransform placed = scale_then_translate(1.2, Vec3(0, 0, 0.3));
  std::vector<SceneMesh> water;
  Vec3 lo = Vec3::Constant(1e30), hi = Vec3::Constant(-1e30);
  for (int f = 14; f <= 24; ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "mesh/fluid_mesh_%04d.bobj.gz", f);
    InputMesh m = read_mesh(bake / name);
    apply_transform(placed, m.mesh, bake / name);
    SceneMesh s;
    for (const Vec3& p : m.mesh.positions) {
      s.positions.push_back(to_povray(p, Axis::z));
      lo = lo.cwiseMin(s.positions.back());
      hi = hi.cwiseMax(s.positions.back());
    }
    for (const Triangle& t : m.mesh.triangles) s.triangles.push_back(t);
    s.min = lo;
    s.max = hi;
    water.push_back(std::move(s));
  }
  const ScreenProjection screen =
      screen_projection(frame_camera(SceneConfig{}, Axis::z, lo, hi), 640, 360);
  const DropletOptions options;
  DropletTracks tracks;
  std::size_t last_found = 0, carried = 0, found_before = 0;
  std::vector<std::size_t> counts;
  std::vector<double> misses;  // pixels from a continued droplet to where it was expected
  for (int f = 14; f <= 24; ++f) {
    char name[64];
    std::snprintf(name, sizeof name, "particles/fluid_particles_%04d.vdb", f);
    const ParticleSet set = read_particles(bake / name);
    std::vector<Vec3> spray, velocities;
    for (std::size_t i = 0; i < set.positions.size(); ++i)
      if (set.kinds[i] == ParticleKind::spray) {
        spray.push_back(to_povray(placed.linear * set.positions[i] + placed.translation, Axis::z));
        velocities.push_back(to_povray(placed.linear * set.velocities.at(i), Axis::z));
      }
    const std::vector<Vec3> expected = tracks.predicted();
    const std::vector<Droplet> drawn = tracks.update(
        spray_droplets(spray, screen, options, &water[static_cast<std::size_t>(f - 14)], expected,
                       velocities),
        screen, options);
    for (const Droplet& d : drawn)
      if (!d.fading && d.age > 0 && d.gathered_at >= 0)
        misses.push_back((*screen.pixel(d.centre) -
                          *screen.pixel(expected[static_cast<std::size_t>(d.gathered_at)]))
                             .norm());
    const std::size_t found = static_cast<std::size_t>(
        std::count_if(drawn.begin(), drawn.end(), [](const Droplet& d) { return !d.fading; }));
    const std::size_t matched = static_cast<std::size_t>(std::count_if(
        drawn.begin(), drawn.end(), [](const Droplet& d) { return !d.fading && d.age > 0; }));
    if (f > 14) {
      carried += matched;
      found_before += last_found;
    }
    std::printf("frame %d: %zu spray particles, %zu droplets drawn, %zu found, %zu carried on\n", f,
                spray.size(), drawn.size(), found, matched);
    counts.push_back(drawn.size());
    last_found = found;
    EXPECT_LE(found, options.max_droplets) << f;
    EXPECT_GE(found, 5u) << f << ": the crown's spray is drawn";
  }
  std::sort(counts.begin(), counts.end());
  EXPECT_LE(counts[counts.size() / 2], 50u) << "a few dozen droplets at 640×360";
  const double share = static_cast<double>(carried) / static_cast<double>(found_before);
  std::printf("droplets found again in the next frame: %.0f %%\n", 100.0 * share);
  // Issue 33 asks for 80 %: gathered first where their particles' velocity (at its fitted
  // scale) takes the last frame's droplets, continued by what is gathered there, and kept while
  // they skim the surface: 84 % (2026-12-05; 78 % expected by their last motion and matched by
  // distance alone, 64 % by place and last motion).
  EXPECT_GE(share, 0.80);
  // Found again where their particles went: a droplet continued is, in the median, less than
  // its size from where its particles' velocity took it (6.9 px; 90 % within 15 px).
  ASSERT_FALSE(misses.empty());
  std::nth_element(misses.begin(), misses.begin() + misses.size() / 2, misses.end());
  std::printf("continued droplets from where they were expected, median: %.1f px\n",
              misses[misses.size() / 2]);
  EXPECT_LE(misses[misses.size() / 2], options.size_pixels);
}

// The camera a scene.pov declares.
CameraPlacement scene_camera(const fs::path& scene_pov) {
  const std::string text = read_text(scene_pov);
  CameraPlacement c;
  auto vector_after = [&](const std::string& key) {
    const std::size_t at = text.find(key + " <");
    Vec3 v = Vec3::Zero();
    if (at != std::string::npos)
      std::sscanf(text.c_str() + at + key.size() + 2, "%lf, %lf, %lf", &v.x(), &v.y(), &v.z());
    return v;
  };
  c.location = vector_after("location");
  c.look_at = vector_after("look_at");
  const std::size_t angle = text.find("\n  angle ");
  if (angle != std::string::npos) std::sscanf(text.c_str() + angle + 9, "%lf", &c.angle);
  return c;
}

// A drawn droplet as its include writes it: Toon_droplet(<centre>, radius, <tail>, line, ...).
struct DrawnDroplet {
  Vec3 centre, tail;
  double radius = 0.0, line = 0.0;
};

std::vector<DrawnDroplet> drawn_droplets(const fs::path& include) {
  const std::string text = read_text(include);
  std::vector<DrawnDroplet> out;
  for (std::size_t at = text.find("Toon_droplet(<"); at != std::string::npos;
       at = text.find("Toon_droplet(<", at + 1)) {
    DrawnDroplet d;
    if (std::sscanf(text.c_str() + at, "Toon_droplet(<%lf,%lf,%lf>, %lf, <%lf,%lf,%lf>, %lf",
                    &d.centre.x(), &d.centre.y(), &d.centre.z(), &d.radius, &d.tail.x(),
                    &d.tail.y(), &d.tail.z(), &d.line) == 8)
      out.push_back(d);
  }
  return out;
}

// The dam break's crown at frame 21 with the spray example's look (antialiased, 640×360):
// every droplet drawn in the air is outlined around its silhouette. A ray from a droplet's
// centre outward must cross line pixels before the sky; only rays whose edge lies against the
// sky (in the same scene rendered without particles) count, so droplets in front of or behind
// the water are judged where they stand in the air.
TEST(SprayRender, TheDamBreaksDropletsInTheAirAreOutlinedAllRound) {
  const fs::path data = shared_dir().empty() ? fs::path() : shared_dir() / "data";
  const fs::path bake = data / "mantaflow-dambreak" / "cache";
  if (data.empty() || !fs::exists(bake / "particles"))
    GTEST_SKIP() << "../shared/data/mantaflow-dambreak is absent: real-data test skipped";
  ScratchDir dir;
  auto povgen = [&](const std::string& name, bool particles) {
    std::vector<std::string> args{
        "povgen",
        "--config",
        (fs::path(TOONWATER_SOURCE_DIR) / "examples" / "spray" / "scene.toml").string(),
        "--water",
        (bake / "mesh" / "fluid_mesh_####.bobj.gz").string(),
        "--scale",
        "1.2",
        "--translate",
        "0,0,0.3",
        "--up",
        "z",
        "--set",
        "render.frames=\"21\"",
        "--out",
        (dir / name).string()};
    if (particles)
      args.insert(args.end(),
                  {"--particles", (bake / "particles" / "fluid_particles_####.vdb").string()});
    const CommandResult r = run_toonwater(args);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const Povray p = run_povray(dir / name);
    ASSERT_EQ(p.exit_code, 0) << p.output;
  };
  povgen("spray", true);
  povgen("bare", false);
  if (HasFatalFailure()) return;
  const ScreenProjection screen =
      screen_projection(scene_camera(dir / "spray" / "scene.pov"), 640, 360);
  std::size_t in_air = 0;
  {
    // One frame of a sequence is a still: frame.png, its includes numbered 0.
    const Image image = read_image(dir / "spray" / "frame.png");
    const Image bare = read_image(dir / "bare" / "frame.png");
    const Rgb8 sky = bare.at(0, 0);
    const fs::path include = "spray_0000.inc";
    for (const DrawnDroplet& d : drawn_droplets(dir / "spray" / include)) {
      const std::optional<Eigen::Vector2d> centre = screen.pixel(d.centre);
      ASSERT_TRUE(centre);
      const double pixel_width = screen.pixel_size(d.centre);
      const double reach = (2 * (d.radius + d.line) + (d.tail - d.centre).norm()) / pixel_width + 4;
      int rays = 0, outlined = 0;
      for (int a = 0; a < 72; ++a) {
        const Eigen::Vector2d step(std::cos(a * std::numbers::pi / 36.0),
                                   std::sin(a * std::numbers::pi / 36.0));
        std::optional<bool> lined;  // none: the ray ran into the water or out of the picture
        Eigen::Vector2d at = *centre;
        for (double r = 0.5; r <= reach && !lined; r += 0.5) {
          at = *centre + r * step;
          if (at.x() < 0 || at.y() < 0 || at.x() >= image.width || at.y() >= image.height) break;
          const Rgb8 p = pixel(image, at.x(), at.y());
          if (is_line(p))
            lined = true;
          else if (near(p, sky, 8))
            lined = false;
        }
        const Eigen::Vector2d beyond = at + 2.0 * step;
        if (!lined || !near(pixel(bare, beyond.x(), beyond.y()), sky, 8)) continue;
        ++rays;
        outlined += *lined ? 1 : 0;
      }
      if (rays < 36) continue;  // less than half its edge against the sky: not in the air
      ++in_air;
      EXPECT_GE(outlined, 0.9 * rays)
          << "the droplet at " << centre->x() << ", " << centre->y() << " is outlined along "
          << outlined << " of " << rays << " rays";
    }
  }
  std::printf("droplets in the air: %zu\n", in_air);
  EXPECT_GE(in_air, 5u) << "the crown throws droplets into the air";
}

// The foam pixels of an image, as a mask.
std::vector<bool> foam_mask(const Image& image) {
  std::vector<bool> mask(static_cast<std::size_t>(image.width) * image.height);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      mask[static_cast<std::size_t>(y) * image.width + x] = is_foam(image.at(x, y));
  return mask;
}

// The dam break's foam over frames 19–22 (the crown falling back over the sphere), placed like
// its spray, at 320×180: patches on the water in every frame, and a patch of one frame still
// has foam within a few pixels in the next (the water moves 2–6 pixels a frame there).
TEST(FoamRender, TheDamBreaksFoamIsPatchesThatFollowTheWater) {
  const fs::path data = shared_dir().empty() ? fs::path() : shared_dir() / "data";
  const fs::path bake = data / "mantaflow-dambreak" / "cache";
  if (data.empty() || !fs::exists(bake / "particles"))
    GTEST_SKIP() << "../shared/data/mantaflow-dambreak is absent: real-data test skipped";
  ScratchDir dir;
  std::vector<std::string> args{"povgen",
                                "--water",
                                (bake / "mesh" / "fluid_mesh_####.bobj.gz").string(),
                                "--scale",
                                "1.2",
                                "--translate",
                                "0,0,0.3",
                                "--up",
                                "z",
                                "--particles",
                                (bake / "particles" / "fluid_particles_####.vdb").string(),
                                "--set",
                                "render.frames=\"19-22\"",
                                "--set",
                                "render.width=320",
                                "--set",
                                "render.height=180",
                                "--out",
                                (dir / "scene").string()};
  args.insert(args.end(), kMagentaFoam.begin(), kMagentaFoam.end());
  const CommandResult r = run_toonwater(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Povray p = run_povray(dir / "scene");
  ASSERT_EQ(p.exit_code, 0) << p.output;
  constexpr int kReach = 3;  // pixels a patch may move between frames
  std::vector<bool> last;
  double kept_sum = 0.0;
  int pairs = 0;
  for (int f = 19; f <= 22; ++f) {
    const Image image = read_image(dir / "scene" / ("frame_" + std::to_string(f) + ".png"));
    const std::vector<bool> mask = foam_mask(image);
    const auto count = std::count(mask.begin(), mask.end(), true);
    EXPECT_GE(count, 100) << "frame " << f << ": the splash's foam is drawn";
    EXPECT_LE(count, image.width * image.height / 10) << "frame " << f << ": foam, not a flood";
    if (!last.empty()) {
      long had = 0, kept = 0;
      for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
          if (!last[static_cast<std::size_t>(y) * image.width + x]) continue;
          ++had;
          bool near_foam = false;
          for (int dy = -kReach; dy <= kReach && !near_foam; ++dy)
            for (int dx = -kReach; dx <= kReach && !near_foam; ++dx) {
              const int u = x + dx, v = y + dy;
              near_foam = u >= 0 && v >= 0 && u < image.width && v < image.height &&
                          mask[static_cast<std::size_t>(v) * image.width + u];
            }
          kept += near_foam ? 1 : 0;
        }
      const double share = static_cast<double>(kept) / static_cast<double>(had);
      std::printf("frame %d: %ld foam pixels, %.0f %% of the last frame's have foam within %d px\n",
                  f, static_cast<long>(count), 100.0 * share, kReach);
      kept_sum += share;
      ++pairs;
    }
    last = mask;
  }
  EXPECT_GE(kept_sum / pairs, 0.7) << "foam follows the water instead of flickering";
}

}  // namespace
}  // namespace toonwater::test
