// povgen scenes rendered with POV-Ray at tiny sizes, pixels read back with OpenImageIO.
// Colours are sRGB in the config and in the PNG, so flat pixels are the configured colours × 255.
#include "tests/support/povray_test_util.hpp"

#include "analyzer/colormap.hpp"
#include "report/image.hpp"
#include "tests/analyzer/water_meshes.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numbers>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

// Writes a scene with toonwater povgen and renders it; returns the frame's image.
Image render_scene(const ScratchDir& dir, const std::string& name, std::vector<std::string> args) {
  const fs::path out = dir / name;
  std::vector<std::string> full{"povgen", "--out", out.string()};
  full.insert(full.end(), args.begin(), args.end());
  const CommandResult r = run_toonwater(full);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const Povray p = run_povray(out);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  return read_image(out / "frame.png");
}

std::string color(const std::array<double, 3>& c) {
  std::string s(1, '[');  // appended piecewise: GCC 12 warns falsely on "literal" + string&&
  s.append(std::to_string(c[0])).append(", ").append(std::to_string(c[1]));
  return s.append(", ").append(std::to_string(c[2])).append("]");
}

const std::array<double, 3> kBright{0.9, 0.9, 0.2}, kMedium{0.2, 0.6, 0.9}, kDark{0.1, 0.1, 0.5},
    kBackground{1, 1, 1}, kObject{0.9, 0.5, 0.1};

std::vector<std::string> opaque_flat_water() {
  return {"--set", "water.ks=0",
          "--set", "water.reflection=0",
          "--set", "water.transmit=0",
          "--set", "render.antialias=false",
          "--set", "render.background=" + color(kBackground),
          "--set", "flow.enabled=false"};
}

bool orange(const Rgb8& c) { return c[0] > c[2] + 60 && c[0] > c[1] + 20; }

// `light` is the config's light setting (input axes, y up); `to_light(p)` the unit vector from a
// surface point p (POV-Ray axes) to the light.
void expect_three_crisp_bands(const std::string& light,
                              const std::function<Vec3(const Vec3&)>& to_light) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_sphere(Vec3::Zero(), 1.0, 48, 96));
  const int W = 64, H = 48;
  const double angle = 40, t_bright = 0.6, t_medium = 0.0;
  const Image img =
      render_scene(dir, "bands",
                   std::vector<std::string>{"--water", (dir / "water.obj").string(),
                                            "--set",   "outline.enabled=false",
                                            "--set",   "water.bright=" + color(kBright),
                                            "--set",   "water.medium=" + color(kMedium),
                                            "--set",   "water.dark=" + color(kDark),
                                            "--set",   "water.t_bright=0.6",
                                            "--set",   "water.t_medium=0.0",
                                            "--set",   light,
                                            "--set",   "camera.location=[0, 0, 5]",
                                            "--set",   "camera.look_at=[0, 0, 0]",
                                            "--set",   "camera.angle=40",
                                            "--set",   "render.width=64",
                                            "--set",   "render.height=48"} +
                       opaque_flat_water());
  ASSERT_EQ(img.width, W);
  const Rgb8 bright = to_rgb8(kBright[0], kBright[1], kBright[2]);
  const Rgb8 medium = to_rgb8(kMedium[0], kMedium[1], kMedium[2]);
  const Rgb8 dark = to_rgb8(kDark[0], kDark[1], kDark[2]);
  const Rgb8 background = to_rgb8(1, 1, 1);

  // POV-Ray's frame: y-up input (x, y, z) -> (x, y, -z); camera at -5 z looking at +z.
  const Vec3 eye(0, 0, -5);
  const double aspect = double(W) / H;
  const double focal = 0.5 * aspect / std::tan(angle / 2 * std::numbers::pi / 180);
  int counts[4] = {0, 0, 0, 0}, checked = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Rgb8 c = img.at(x, y);
      const bool known = near(c, bright) || near(c, medium) || near(c, dark) || near(c, background);
      ASSERT_TRUE(known) << "pixel " << x << "," << y << " has a colour outside the bands";
      counts[0] += near(c, bright), counts[1] += near(c, medium), counts[2] += near(c, dark);
      counts[3] += near(c, background);
      const Vec3 ray =
          Vec3(aspect * ((x + 0.5) / W - 0.5), 0.5 - (y + 0.5) / H, focal).normalized();
      const double b = eye.dot(ray), miss = b * b - eye.squaredNorm();  // |eye + t ray| = r
      const double closest = std::sqrt(std::max(0.0, eye.squaredNorm() - b * b));
      if (std::abs(closest - 1.0) < 0.04) continue;  // the silhouette: the mesh is polygonal
      if (closest > 1.0) {
        EXPECT_TRUE(near(c, background)) << x << "," << y;
        continue;
      }
      const double t = -b - std::sqrt(miss + 1.0);
      const Vec3 n = (eye + t * ray).normalized();
      const double l_dot_n = to_light(n).dot(n);  // on the unit sphere, the point is n
      if (std::abs(l_dot_n - t_bright) < 0.04 || std::abs(l_dot_n - t_medium) < 0.04) continue;
      const Rgb8 expected = l_dot_n > t_bright ? bright : l_dot_n > t_medium ? medium : dark;
      EXPECT_TRUE(near(c, expected)) << "pixel " << x << "," << y << " L.n " << l_dot_n;
      ++checked;
    }
  EXPECT_GT(checked, 600);
  for (int band = 0; band < 3; ++band) EXPECT_GT(counts[band], 40) << "band " << band;
}

TEST(PovgenRender, ThreeCrispBandsWhereTheThresholdsPutThemForAParallelLight) {
  expect_three_crisp_bands("light.direction=[1, 1, 1]",
                           [](const Vec3&) { return Vec3(1, 1, -1).normalized(); });
}

TEST(PovgenRender, ThreeCrispBandsWhereTheThresholdsPutThemForAPointLight) {
  // At (1.5, 1.5, 1.5) in y-up input axes: (1.5, 1.5, -1.5) in POV-Ray's.
  expect_three_crisp_bands("light.position=[1.5, 1.5, 1.5]",
                           [](const Vec3& p) { return (Vec3(1.5, 1.5, -1.5) - p).normalized(); });
}

// By default the band thresholds sit around the calm water's L·n: flat water is the medium
// band, the slope of a bump facing the light bright, the slope facing away dark. Absolute
// thresholds (0.7 and 0.2 under the default sun, whose L·n on flat water is 0.815) put all of
// the flat water in the bright band.
// A coarse sphere (30° between rings) under a medium band narrower than the step of L·n from a
// vertex to the next: its faces go from a dark corner straight to a bright one. Interpolated,
// u would pass through the medium band and paint a sliver across each of them; they get two
// bands instead (band_crossings.hpp), so the sphere is dark and bright, the edge between them
// where it turns from the light, and not one pixel is medium. The mesh's own normals: smoothed
// ones (the default) would round a sphere this coarse off.
TEST(PovgenRender, WhereDarkMeetsBrightNoMediumSliverLiesBetween) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_sphere(Vec3::Zero(), 1.0, 6, 12));
  const int W = 96, H = 72;
  const double angle = 40, t_edge = 0.325;  // halfway between the thresholds
  const Image img =
      render_scene(dir, "coarse",
                   std::vector<std::string>{"--water", (dir / "water.obj").string(),
                                            "--set",   "outline.enabled=false",
                                            "--set",   "water.bright=" + color(kBright),
                                            "--set",   "water.medium=" + color(kMedium),
                                            "--set",   "water.dark=" + color(kDark),
                                            "--set",   "water.t_bright=0.35",
                                            "--set",   "water.t_medium=0.3",
                                            "--set",   "water.normals=\"mesh\"",
                                            "--set",   "light.direction=[1, 0, 1]",
                                            "--set",   "camera.location=[0, 0, 5]",
                                            "--set",   "camera.look_at=[0, 0, 0]",
                                            "--set",   "camera.angle=40",
                                            "--set",   "render.width=96",
                                            "--set",   "render.height=72"} +
                       opaque_flat_water());
  ASSERT_EQ(img.width, W);
  const Rgb8 bright = to_rgb8(kBright[0], kBright[1], kBright[2]);
  const Rgb8 medium = to_rgb8(kMedium[0], kMedium[1], kMedium[2]);
  const Rgb8 dark = to_rgb8(kDark[0], kDark[1], kDark[2]);
  const Rgb8 background = to_rgb8(1, 1, 1);
  // POV-Ray's frame, as in expect_three_crisp_bands; the light's direction (1, 0, 1) becomes
  // (1, 0, −1).
  const Vec3 eye(0, 0, -5), to_light = Vec3(1, 0, -1).normalized();
  const double aspect = double(W) / H;
  const double focal = 0.5 * aspect / std::tan(angle / 2 * std::numbers::pi / 180);
  int counts[3] = {0, 0, 0}, checked = 0;
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const Rgb8 c = img.at(x, y);
      ASSERT_TRUE(near(c, bright) || near(c, medium) || near(c, dark) || near(c, background))
          << "pixel " << x << "," << y << " has a colour outside the bands";
      counts[0] += near(c, bright), counts[1] += near(c, medium), counts[2] += near(c, dark);
      const Vec3 ray =
          Vec3(aspect * ((x + 0.5) / W - 0.5), 0.5 - (y + 0.5) / H, focal).normalized();
      const double b = eye.dot(ray);
      const double closest = std::sqrt(std::max(0.0, eye.squaredNorm() - b * b));
      if (closest > 0.9) continue;  // the coarse sphere's polygonal silhouette
      const Vec3 n = (eye + (-b - std::sqrt(b * b - eye.squaredNorm() + 1.0)) * ray).normalized();
      // A face spans 30°: its corners' L·n differ by up to half, so the edge between the bands
      // lies within a quarter of it from where the ideal sphere has it.
      const double l_dot_n = to_light.dot(n);
      if (std::abs(l_dot_n - t_edge) < 0.25) continue;
      EXPECT_TRUE(near(c, l_dot_n > t_edge ? bright : dark))
          << "pixel " << x << "," << y << " L.n " << l_dot_n;
      ++checked;
    }
  EXPECT_EQ(counts[1], 0) << "medium pixels";
  EXPECT_GT(counts[0], 300) << "bright pixels";
  EXPECT_GT(counts[2], 300) << "dark pixels";
  EXPECT_GT(checked, 600);
}

TEST(PovgenRender, RelativeBandsPutCalmWaterInTheMiddleBand) {
  ScratchDir dir;
  write_obj(dir / "bump.obj", make_height_grid(81, 1.0, [](double x, double z) {
              return 0.05 * std::exp(-(x * x + z * z) / 0.03);
            }));
  const std::vector<std::string> args =
      std::vector<std::string>{"--water", (dir / "bump.obj").string(),
                               "--set",   "outline.enabled=false",
                               "--set",   "water.bright=" + color(kBright),
                               "--set",   "water.medium=" + color(kMedium),
                               "--set",   "water.dark=" + color(kDark),
                               "--set",   "camera.location=[0, 2.5, 2.5]",
                               "--set",   "camera.look_at=[0, 0, 0]",
                               "--set",   "render.width=64",
                               "--set",   "render.height=48"} +
      opaque_flat_water();
  const Rgb8 bright = to_rgb8(kBright[0], kBright[1], kBright[2]);
  const Rgb8 medium = to_rgb8(kMedium[0], kMedium[1], kMedium[2]);
  const Rgb8 dark = to_rgb8(kDark[0], kDark[1], kDark[2]);
  auto count = [](const Image& img, const Rgb8& c) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) n += near(img.at(x, y), c, 1);
    return n;
  };
  const Image relative = render_scene(dir, "relative", args);
  EXPECT_TRUE(near(relative.at(4, 40), medium)) << "calm water in the middle band";
  EXPECT_TRUE(near(relative.at(60, 40), medium));
  EXPECT_GT(count(relative, medium), 800);
  EXPECT_GT(count(relative, bright), 15) << "the slope facing the light";
  EXPECT_GT(count(relative, dark), 15) << "the slope facing away";
  const Image absolute = render_scene(
      dir, "absolute", args + std::vector<std::string>{"--set", "water.bands=absolute"});
  EXPECT_TRUE(near(absolute.at(4, 40), bright));
  EXPECT_LT(count(absolute, medium) + count(absolute, dark), 40);
}

// Calm water carrying marching-cubes-like jitter of 0.15 cells, vertex by vertex, as a level set
// meshed on a grid has it: one band and no flow region (the shading normals are smoothed over
// the cells' scale, the band limits and the flow threshold sit above the data's noise), while
// a wave of a few cells on the same jitter still shows in both.
TEST(PovgenRender, CalmNoisyWaterIsOneBandWithoutFlow) {
  ScratchDir dir;
  constexpr int n = 81;
  constexpr double cell = 2.0 / (n - 1);
  auto jitter = [](double x, double z) {  // 0.15 cells
    return 0.15 * cell * std::sin(12.9898 * std::round(x / cell) + 78.233 * std::round(z / cell)) *
           std::cos(43758.5453 * std::round(x / cell) - 9.1 * std::round(z / cell));
  };
  write_obj(dir / "calm.obj", make_height_grid(n, 1.0, jitter));
  write_obj(dir / "wave.obj", make_height_grid(n, 1.0, [&](double x, double z) {
              return jitter(x, z) + 0.2 * std::exp(-(x * x + z * z) / 0.04);
            }));
  const std::array<double, 3> ridge{1, 0, 0}, valley{0, 1, 0};
  auto args = [&](const std::string& mesh, bool flow = true,
                  const std::string& normals = "smoothed") {
    return std::vector<std::string>{"--water", (dir / mesh).string(),
                                    "--set",   "outline.enabled=false",
                                    "--set",   "water.bright=" + color(kBright),
                                    "--set",   "water.medium=" + color(kMedium),
                                    "--set",   "water.dark=" + color(kDark),
                                    "--set",   "camera.location=[0, 2.5, 2.5]",
                                    "--set",   "camera.look_at=[0, 0, 0]",
                                    "--set",   "render.width=96",
                                    "--set",   "render.height=72"} +
           opaque_flat_water() +
           std::vector<std::string>{"--set", flow ? "flow.enabled=true" : "flow.enabled=false",
                                    "--set", "water.normals=\"" + normals + "\"",
                                    "--set", "flow.ridge_color=" + color(ridge),
                                    "--set", "flow.valley_color=" + color(valley)};
  };
  auto count = [](const Image& img, const std::array<double, 3>& c) {
    const Rgb8 want = to_rgb8(c[0], c[1], c[2]);
    int k = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) k += near(img.at(x, y), want, 1);
    return k;
  };
  const Image calm = render_scene(dir, "calm", args("calm.obj"));
  const int water = count(calm, kBright) + count(calm, kMedium) + count(calm, kDark);
  EXPECT_GT(water, 3000);
  EXPECT_EQ(count(calm, kMedium), water) << "every pixel of calm water in the middle band";
  EXPECT_EQ(count(calm, ridge) + count(calm, valley), 0) << "no flow on calm water";
  const Image wave = render_scene(dir, "wave", args("wave.obj"));
  EXPECT_GT(count(wave, kBright), 20) << "the wave's slope facing the light";
  EXPECT_GT(count(wave, kDark), 20) << "the slope facing away";
  EXPECT_GT(count(wave, ridge), 20) << "its crest";
  // Flow regions turned off: the bands still come from the smoothed shading normals, kept above
  // their noise floor, so calm water under jitter of a whole cell stays one band; from the
  // mesh's own normals (water.normals = "mesh"), with no noise floor, the jitter shows.
  write_obj(dir / "rough.obj",
            make_height_grid(n, 1.0, [&](double x, double z) { return jitter(x, z) / 0.15; }));
  const Image rough = render_scene(dir, "rough", args("rough.obj", false));
  EXPECT_GT(count(rough, kMedium), 3000);
  EXPECT_EQ(count(rough, kBright) + count(rough, kDark), 0) << "flow off: one band";
  const Image facets = render_scene(dir, "facets", args("rough.obj", false, "mesh"));
  EXPECT_GT(count(facets, kBright) + count(facets, kDark), 150) << "the mesh's own normals";
}

// Band limits inside the noise (explicit, so not raised above it) on the mesh's own normals
// (water.normals = "mesh") of a surface jittered by up to a cell: the noise paints specks of every
// band over calm water. Patches smaller than the shading's scale or 2 px on screen take the colour
// around them (water.min_patch, scene/toon_islands.hpp): the specks go, while a wave's slopes,
// larger than both, keep their bands.
TEST(PovgenRender, SpecksOfTheBandsTakeTheColourAroundThem) {
  ScratchDir dir;
  constexpr int n = 81;
  constexpr double cell = 2.0 / (n - 1);
  write_obj(dir / "noisy.obj", make_height_grid(n, 1.0, [&](double x, double z) {
              const double noise =
                  cell * std::sin(12.9898 * std::round(x / cell) + 78.233 * std::round(z / cell)) *
                  std::cos(43758.5453 * std::round(x / cell) - 9.1 * std::round(z / cell));
              return noise + 0.2 * std::exp(-(x * x + z * z) / 0.04);
            }));
  auto args = [&](const std::string& min_patch) {
    return std::vector<std::string>{"--water", (dir / "noisy.obj").string(),
                                    "--set",   "outline.enabled=false",
                                    "--set",   "water.bright=" + color(kBright),
                                    "--set",   "water.medium=" + color(kMedium),
                                    "--set",   "water.dark=" + color(kDark),
                                    "--set",   "water.dt_bright=0.1",
                                    "--set",   "water.dt_medium=-0.1",
                                    "--set",   "water.normals=\"mesh\"",
                                    "--set",   "camera.location=[0, 2.5, 2.5]",
                                    "--set",   "camera.look_at=[0, 0, 0]",
                                    "--set",   "render.width=160",
                                    "--set",   "render.height=120",
                                    "--set",   "water.min_patch=" + min_patch} +
           opaque_flat_water();
  };
  // The 4-connected patches of each band colour smaller than a disc of 2 px, and the pixels of
  // the bright and dark bands.
  struct Patches {
    int specks = 0, bright = 0, dark = 0;
  };
  auto patches = [](const Image& img) {
    Patches p;
    std::vector<int> band(static_cast<std::size_t>(img.width * img.height), -1);
    const std::array<std::array<double, 3>, 3> colors{kBright, kMedium, kDark};
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int b = 0; b < 3; ++b)
          if (near(img.at(x, y), to_rgb8(colors[b][0], colors[b][1], colors[b][2]), 1))
            band[static_cast<std::size_t>(y * img.width + x)] = b;
    std::vector<bool> seen(band.size(), false);
    for (std::size_t start = 0; start < band.size(); ++start) {
      if (band[start] < 0 || seen[start]) continue;
      std::vector<std::size_t> stack{start};
      seen[start] = true;
      int size = 0;
      while (!stack.empty()) {
        const std::size_t i = stack.back();
        stack.pop_back();
        ++size;
        const int x = static_cast<int>(i) % img.width, y = static_cast<int>(i) / img.width;
        const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
        for (int k = 0; k < 4; ++k) {
          if (nx[k] < 0 || ny[k] < 0 || nx[k] >= img.width || ny[k] >= img.height) continue;
          const auto j = static_cast<std::size_t>(ny[k] * img.width + nx[k]);
          if (!seen[j] && band[j] == band[start]) seen[j] = true, stack.push_back(j);
        }
      }
      p.specks += size < 13;
    }
    for (int b : band) p.bright += b == 0, p.dark += b == 2;
    return p;
  };
  const Patches raw = patches(render_scene(dir, "raw", args("0")));
  const Patches merged = patches(render_scene(dir, "merged", args("2")));
  EXPECT_GE(raw.specks, 40) << "the noise crosses the band limits";
  EXPECT_LE(8 * merged.specks, raw.specks) << "left: slivers along the wave's ragged band edges";
  EXPECT_GT(merged.bright, 100) << "the wave's slope facing the light";
  EXPECT_GT(merged.dark, 100) << "the slope facing away";
}

// White noise in [-1, 1) per grid point (of spacing `cell`) and frame: splitmix64's finaliser.
double white_noise(double x, double z, double cell, int frame) {
  std::uint64_t h = static_cast<std::uint64_t>(std::lround(x / cell) + 1000) * 1000003u +
                    static_cast<std::uint64_t>(std::lround(z / cell) + 1000) * 7919u +
                    static_cast<std::uint64_t>(frame) * 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  h ^= h >> 31;
  return static_cast<double>(h >> 11) * 0x1p-52 - 1.0;
}

// Settling water: a swell of 2.5 cells creeping 0.03 cells a frame under jitter of 0.1 cells that
// each frame draws afresh, as a level set meshed anew every frame has it, seen from above. The
// bands follow the swell, not the jitter: carried from frame to frame with the flow field
// (flow.coherence, flow_coherence.hpp), the shading normals leave under 1 % of the water's
// pixels changing band a frame, and well under what they do frame by frame.
TEST(PovgenRender, SettlingWaterChangesBandOnlyWhereItMoves) {
  ScratchDir dir;
  constexpr int n = 81, frames = 6;
  constexpr double cell = 2.0 / (n - 1);
  for (int f = 1; f <= frames; ++f)
    write_obj(dir / ("water_" + std::to_string(f) + ".obj"),
              make_height_grid(n, 1.0, [&](double x, double z) {
                const double jitter = 0.1 * cell * white_noise(x, z, cell, f);
                const double swell = 2.5 * cell *
                                     std::sin(2 * std::numbers::pi * (x - 0.03 * cell * f) / 0.5) *
                                     std::cos(2 * std::numbers::pi * z / 0.7);
                return swell + jitter;
              }));
  auto changes = [&](const std::string& name, bool coherence) {
    const fs::path out = dir / name;
    std::vector<std::string> args{"povgen",
                                  "--out",
                                  out.string(),
                                  "--water",
                                  (dir / "water_#.obj").string(),
                                  "--set",
                                  "outline.enabled=false",
                                  "--set",
                                  "water.bright=" + color(kBright),
                                  "--set",
                                  "water.medium=" + color(kMedium),
                                  "--set",
                                  "water.dark=" + color(kDark),
                                  "--set",
                                  "camera.location=[0, 10, 0.0001]",
                                  "--set",
                                  "camera.look_at=[0, 0, 0]",
                                  "--set",
                                  "camera.angle=11",
                                  "--set",
                                  "render.width=320",
                                  "--set",
                                  "render.height=320"};
    args =
        args + opaque_flat_water() +
        std::vector<std::string>{"--set", "flow.enabled=true", "--set",
                                 std::string("flow.coherence=") + (coherence ? "true" : "false")};
    const CommandResult r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(run_povray(out).exit_code, 0);
    const std::array<std::array<double, 3>, 3> colors{kBright, kMedium, kDark};
    std::vector<int> before;
    double changed = 0.0;
    int bright_and_dark = 0, water = 0;
    for (int f = 1; f <= frames; ++f) {
      const Image img = read_image(out / ("frame_" + std::to_string(f) + ".png"));
      std::vector<int> band(static_cast<std::size_t>(img.width * img.height), -1);
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
          for (int b = 0; b < 3; ++b)
            if (near(img.at(x, y), to_rgb8(colors[b][0], colors[b][1], colors[b][2]), 1))
              band[static_cast<std::size_t>(y * img.width + x)] = b;
      int differ = 0, both = 0;
      for (std::size_t i = 0; i < band.size() && !before.empty(); ++i)
        if (band[i] >= 0 && before[i] >= 0) ++both, differ += band[i] != before[i];
      if (!before.empty())
        changed += static_cast<double>(differ) / std::max(1, both) / (frames - 1);
      for (int b : band) water += b >= 0, bright_and_dark += b == 0 || b == 2;
      before = std::move(band);
    }
    EXPECT_GT(bright_and_dark, water / 5) << "the swell shows in the bands";
    return changed;
  };
  const double frame_by_frame = changes("frame_by_frame", false);
  const double carried = changes("carried", true);
  std::printf("band changes a frame: %.4f frame by frame, %.4f carried\n", frame_by_frame, carried);
  EXPECT_LT(carried, 0.01);
  EXPECT_LT(carried, 0.7 * frame_by_frame);
}

// A crest two cells high along z at x = crest_x(f) under jitter of 0.1 cells that each frame
// draws afresh (a grid over [−1, 1]², meshed anew each frame), seen from above with
// `flow.style = "lines"`, strokes pure red on flat water: each frame's stroke pixels, row-major,
// kCrestImage pixels square; empty when povgen or POV-Ray fails.
constexpr int kCrestGrid = 81, kCrestImage = 320;
constexpr double kCrestCell = 2.0 / (kCrestGrid - 1), kCrestLineWidth = 4.0, kCrestAngle = 11.0;
std::vector<std::vector<std::uint8_t>> crest_strokes(const fs::path& dir, int frames,
                                                     const std::function<double(int)>& crest_x) {
  constexpr double cell = kCrestCell, sigma = 1.5 * kCrestCell;
  for (int f = 1; f <= frames; ++f)
    write_obj(dir / ("water_" + std::to_string(f) + ".obj"),
              make_height_grid(kCrestGrid, 1.0, [&](double x, double z) {
                const double d = x - crest_x(f);
                return 2.0 * cell * std::exp(-d * d / (2 * sigma * sigma)) +
                       0.1 * cell * white_noise(x, z, cell, f);
              }));
  const fs::path out = dir / "strokes";
  std::vector<std::string> args{"povgen", "--out", out.string(), "--water",
                                (dir / "water_#.obj").string()};
  args = args + opaque_flat_water() +
         std::vector<std::string>{"--set", "flow.enabled=true",
                                  "--set", "flow.style=\"lines\"",
                                  "--set", "flow.line_color=[1, 0, 0]",
                                  "--set", "flow.line_width=" + std::to_string(kCrestLineWidth),
                                  "--set", "outline.enabled=false",
                                  "--set", "water.bright=" + color(kMedium),
                                  "--set", "water.medium=" + color(kMedium),
                                  "--set", "water.dark=" + color(kMedium),
                                  "--set", "camera.location=[0, 10, 0.0001]",
                                  "--set", "camera.look_at=[0, 0, 0]",
                                  "--set", "camera.angle=" + std::to_string(kCrestAngle),
                                  "--set", "render.width=" + std::to_string(kCrestImage),
                                  "--set", "render.height=" + std::to_string(kCrestImage)};
  const CommandResult r = run_toonwater(args);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  const Povray rendered = run_povray(out);
  EXPECT_EQ(rendered.exit_code, 0) << rendered.output;
  if (r.exit_code != 0 || rendered.exit_code != 0) return {};
  std::vector<std::vector<std::uint8_t>> stroke;
  for (int f = 1; f <= frames; ++f) {
    const Image img = read_image(out / ("frame_" + std::to_string(f) + ".png"));
    EXPECT_EQ(img.width, kCrestImage);
    EXPECT_EQ(img.height, kCrestImage);
    if (img.width != kCrestImage || img.height != kCrestImage) return {};
    stroke.push_back(mask_of(img, Rgb8{255, 0, 0}));
  }
  return stroke;
}

// A stroke down the picture: its pixels in each row it crosses, their median and how many rows.
struct StrokeRows {
  int rows = 0, median_width = 0;
};
StrokeRows stroke_rows(const std::vector<std::uint8_t>& mask) {
  std::vector<int> across;
  for (int y = 0; y < kCrestImage; ++y) {
    int count = 0;
    for (int x = 0; x < kCrestImage; ++x)
      count += mask[static_cast<std::size_t>(y * kCrestImage + x)];
    if (count > 0) across.push_back(count);
  }
  if (across.empty()) return {};
  std::nth_element(across.begin(), across.begin() + across.size() / 2, across.end());
  return {static_cast<int>(across.size()), across[across.size() / 2]};
}

// The share of a frame's stroke pixels with no stroke pixel within 2 px in the next frame.
double lost_share(const std::vector<std::uint8_t>& before, const std::vector<std::uint8_t>& after) {
  const auto pixels = static_cast<double>(std::count(before.begin(), before.end(), 1));
  return static_cast<double>(report::pixels_without_neighbour(before, after, kCrestImage, 2)) /
         std::max(1.0, pixels);
}

// A crest that stands still: its stroke persists (stroke_persistence.hpp) through the whole
// pipeline, so from the third frame on it is drawn at its full width, and nearly every stroke
// pixel has a stroke pixel within 2 px in the next frame.
TEST(PovgenRender, AStillCrestKeepsOneFullWidthStrokeUnderJitter) {
  ScratchDir dir;
  constexpr int frames = 5;
  const auto stroke = crest_strokes(dir.path(), frames, [](int) { return 0.0; });
  ASSERT_EQ(stroke.size(), static_cast<std::size_t>(frames));
  for (int f = 3; f <= frames; ++f) {
    const StrokeRows rows = stroke_rows(stroke[f - 1]);
    ASSERT_GT(rows.rows, kCrestImage / 4) << "frame " << f;
    EXPECT_GE(rows.median_width, kCrestLineWidth - 1) << "frame " << f << ": a thin stroke";
    if (f < frames) {
      EXPECT_LE(lost_share(stroke[f - 1], stroke[f]), 0.05) << "frames " << f << "-" << f + 1;
    }
  }
}

// A crest travelling 0.4 cells a frame: its stroke glides with it as one unbroken stroke at its
// full width, placed between the vertices where the crest lies (flow_strokes.hpp). Nearly every
// stroke pixel has a stroke pixel within 2 px in the next frame (the crest moves 1.7 px a
// frame). The field that draws it is carried from frame to frame (flow_coherence.hpp) and
// follows a moving crest a cell behind; from the fourth frame on, the stroke keeps the crest's
// pace.
TEST(PovgenRender, ATravellingCrestsStrokeMovesWithItWithoutBreaking) {
  ScratchDir dir;
  constexpr int frames = 8;
  constexpr double cell = kCrestCell;
  auto crest_at = [](int f) { return -0.5 + 0.4 * kCrestCell * f; };
  const auto stroke = crest_strokes(dir.path(), frames, crest_at);
  ASSERT_EQ(stroke.size(), static_cast<std::size_t>(frames));
  // Pixels a unit of length at the water, 10 below the camera.
  const double scale = kCrestImage / (2 * 10 * std::tan(kCrestAngle / 2 * std::numbers::pi / 180));
  std::vector<double> centre;  // the stroke pixels' mean column
  for (int f = 1; f <= frames; ++f) {
    double columns = 0, pixels = 0;
    for (int y = 0; y < kCrestImage; ++y)
      for (int x = 0; x < kCrestImage; ++x)
        if (stroke[f - 1][static_cast<std::size_t>(y * kCrestImage + x)]) columns += x, ++pixels;
    ASSERT_GT(pixels, kCrestImage) << "frame " << f << ": no stroke along the crest";
    centre.push_back(columns / pixels);
  }
  // The crest runs along z, down the picture; which way x runs across it is the camera's
  // business, so the stroke's travel is measured from the first frame, where it is traced.
  const double direction = centre.back() > centre.front() ? 1.0 : -1.0;
  auto travelled = [&](int f) { return direction * (centre[f - 1] - centre[0]) / scale; };
  auto crest_travelled = [&](int f) { return crest_at(f) - crest_at(1); };
  for (int f = 2; f <= frames; ++f) {
    EXPECT_EQ(report::pieces_of(stroke[f - 1], kCrestImage), 1u) << "frame " << f << ": broken";
    EXPECT_GE(stroke_rows(stroke[f - 1]).median_width, kCrestLineWidth - 1)
        << "frame " << f << ": a thin stroke";
    EXPECT_LE(travelled(f), crest_travelled(f) + 0.25 * cell) << "frame " << f << ": ahead";
    EXPECT_GE(travelled(f), crest_travelled(f) - 1.5 * cell) << "frame " << f << ": left behind";
    EXPECT_LE(lost_share(stroke[f - 2], stroke[f - 1]), 0.05) << "frames " << f - 1 << "-" << f;
  }
  const double pace =
      (travelled(frames) - travelled(4)) / (crest_travelled(frames) - crest_travelled(4));
  EXPECT_GT(pace, 0.75) << "the stroke falls behind the crest";
  EXPECT_LT(pace, 1.25) << "the stroke runs ahead of the crest";
}

// A reflected ray that misses every object sees the flat sky colour, not the background: on
// black water that reflects fully, the water shows the sky everywhere but where it reflects
// the ball.
TEST(PovgenRender, ReflectedRaysThatMissEverythingSeeTheSky) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(5, 4.0, [](double, double) { return 0.0; }));
  write_obj(dir / "ball.obj", make_sphere(Vec3(0, 0.9, 0), 0.5, 16, 32));
  const Image img = render_scene(
      dir, "sky",
      std::vector<std::string>{"--water",  (dir / "water.obj").string(),
                               "--object", (dir / "ball.obj").string(),
                               "--set",    "object.0.color=" + color(kObject),
                               "--set",    "water.bright=[0, 0, 0]",
                               "--set",    "water.medium=[0, 0, 0]",
                               "--set",    "water.dark=[0, 0, 0]",
                               "--set",    "water.sky=[0, 0.5, 0]",
                               "--set",    "camera.location=[0, 1.0, 6]",
                               "--set",    "camera.look_at=[0, 0.2, 0]",
                               "--set",    "render.width=64",
                               "--set",    "render.height=48"} +
          opaque_flat_water() + std::vector<std::string>{"--set", "water.reflection=1"});
  const Rgb8 sky = to_rgb8(0, 0.5, 0);
  int sky_pixels = 0, background = 0, reflected_ball = 0;
  for (int y = img.height / 2 + 6; y < img.height; ++y)  // below the horizon: water only
    for (int x = 0; x < img.width; ++x) {
      const Rgb8 c = img.at(x, y);
      sky_pixels += near(c, sky, 2);
      background += near(c, {255, 255, 255}, 2);
      reflected_ball += orange(c);
    }
  EXPECT_GT(sky_pixels, 300);
  EXPECT_EQ(background, 0) << "reflections show the background";
  EXPECT_GT(reflected_ball, 10) << "the ball's reflection reads as the ball";
}

// Outline widths in pixels: two equal spheres, one more than twice as far from the camera as
// the other, get lines of the same width in the picture (3 px here, measured along the row
// through each centre).
TEST(PovgenRender, OutlineWidthInPixelsIsEvenAcrossDepth) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(3, 0.5, [](double, double) { return -50.0; }));
  write_obj(dir / "near.obj", make_sphere(Vec3(-1.0, 0, 0), 0.5, 32, 64));
  write_obj(dir / "far.obj", make_sphere(Vec3(2.5, 0, -8), 0.5, 32, 64));
  const int W = 200, H = 100;
  const Image img =
      render_scene(dir, "widths",
                   std::vector<std::string>{"--water",  (dir / "water.obj").string(),
                                            "--object", (dir / "near.obj").string(),
                                            "--object", (dir / "far.obj").string(),
                                            "--set",    "outline.width=3",
                                            "--set",    "object.0.color=" + color(kObject),
                                            "--set",    "object.1.color=" + color(kObject),
                                            "--set",    "camera.location=[0, 0, 6]",
                                            "--set",    "camera.look_at=[0, 0, 0]",
                                            "--set",    "camera.angle=30",
                                            "--set",    "render.width=" + std::to_string(W),
                                            "--set",    "render.height=" + std::to_string(H)} +
                       opaque_flat_water());
  // Pixel column of a point (input axes, camera on +z looking at the origin).
  const double f = (W / 2.0) / std::tan(15 * std::numbers::pi / 180);
  auto column = [&](double x, double depth) { return W / 2.0 + f * x / depth; };
  auto line_width = [&](double x, double depth) {
    const int centre = static_cast<int>(column(x, depth)), y = H / 2;
    int width = 0;
    for (int u = centre; u >= 0; --u) {
      const bool black = near(img.at(u, y), {0, 0, 0}, 8);
      if (black)
        ++width;
      else if (width > 0)
        break;
    }
    return width;
  };
  const int near_width = line_width(-1.0, 6), far_width = line_width(2.5, 14);
  EXPECT_NEAR(near_width, 3, 1);
  EXPECT_NEAR(far_width, 3, 1);
  EXPECT_LE(std::abs(near_width - far_width), 1) << near_width << " px vs " << far_width << " px";
}

TEST(PovgenRender, OutlineAroundASphereIsARingOfTheExpectedWidth) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(3, 0.5, [](double, double) { return -50.0; }));
  write_obj(dir / "ball.obj", make_sphere(Vec3::Zero(), 1.0, 48, 96));
  const int W = 96;
  const double angle = 30, D = 6, R = 1, w = 0.1;
  const Image img =
      render_scene(dir, "ring",
                   std::vector<std::string>{"--water",  (dir / "water.obj").string(),
                                            "--object", (dir / "ball.obj").string(),
                                            "--set",    "outline.units=world",
                                            "--set",    "outline.width=0.1",
                                            "--set",    "object.0.color=" + color(kObject),
                                            "--set",    "camera.location=[0, 0, 6]",
                                            "--set",    "camera.look_at=[0, 0, 0]",
                                            "--set",    "camera.angle=30",
                                            "--set",    "render.width=96",
                                            "--set",    "render.height=96"} +
                       opaque_flat_water());
  const double f = (W / 2.0) / std::tan(angle / 2 * std::numbers::pi / 180);
  const double r_inner = f * std::tan(std::asin(R / D)),
               r_outer = f * std::tan(std::asin((R + w) / D));
  int black = 0;
  for (int y = 0; y < W; ++y)
    for (int x = 0; x < W; ++x) {
      const double d = std::hypot(x + 0.5 - W / 2.0, y + 0.5 - W / 2.0);
      const bool is_black = near(img.at(x, y), {0, 0, 0}, 8);
      if (d < r_inner - 1.0) {
        EXPECT_FALSE(is_black) << "black inside the object at " << x << "," << y;
      }
      if (d > r_outer + 1.0) {
        EXPECT_FALSE(is_black) << "black outside the ring at " << x << "," << y;
      }
      black += is_black;
    }
  const double annulus = std::numbers::pi * (r_outer * r_outer - r_inner * r_inner);
  EXPECT_NEAR(black, annulus, 0.25 * annulus) << "ring " << r_inner << "-" << r_outer << " px";
  // Continuous: every direction from the centre crosses the ring.
  for (int k = 0; k < 72; ++k) {
    const double a = 2 * std::numbers::pi * k / 72;
    bool hit = false;
    for (double r = r_inner - 1; r <= r_outer + 1; r += 0.25) {
      const int x = int(W / 2.0 + r * std::cos(a)), y = int(W / 2.0 + r * std::sin(a));
      hit = hit || near(img.at(x, y), {0, 0, 0}, 8);
    }
    EXPECT_TRUE(hit) << "gap in the outline at " << k * 5 << " degrees";
  }
}

TEST(PovgenRender, AbstractReflectionShowsOnlyTheFlatSilhouette) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(5, 4.0, [](double, double) { return 0.0; }));
  write_obj(dir / "ball.obj", make_sphere(Vec3(0, 0.9, 0), 0.5, 16, 32));
  auto args = [&](const char* target) {
    return std::vector<std::string>{"--water",  (dir / "water.obj").string(),
                                    "--object", (dir / "ball.obj").string(),
                                    "--set",    "object.0.reflection=" + std::string(target),
                                    "--set",    "object.0.color=" + color(kObject),
                                    "--set",    "outline.color=[0, 1, 0]",
                                    "--set",    "outline.units=world",
                                    "--set",    "outline.width=0.05",
                                    "--set",    "water.bright=[0, 0, 0]",
                                    "--set",    "water.medium=[0, 0, 0]",
                                    "--set",    "water.dark=[0, 0, 0]",
                                    "--set",    "camera.location=[0, 1.0, 6]",
                                    "--set",    "camera.look_at=[0, 0.2, 0]",
                                    "--set",    "render.width=64",
                                    "--set",    "render.height=48"} +
           opaque_flat_water() + std::vector<std::string>{"--set", "water.reflection=1"};
  };
  const Image concrete = render_scene(dir, "concrete", args("concrete"));
  const Image abstract = render_scene(dir, "abstract", args("abstract"));
  const Image none = render_scene(dir, "none", args("none"));
  int reflected = 0, orange_concrete = 0, orange_abstract = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      orange_concrete += orange(concrete.at(x, y));
      orange_abstract += orange(abstract.at(x, y));
      if (near(concrete.at(x, y), abstract.at(x, y), 2)) continue;
      ++reflected;  // differs: part of the reflection
      EXPECT_TRUE(near(abstract.at(x, y), {0, 255, 0}, 2))
          << "abstract reflection pixel " << x << "," << y << " is not the silhouette colour";
      EXPECT_FALSE(near(none.at(x, y), {0, 255, 0}, 2) || orange(none.at(x, y)))
          << "reflection target none still reflected at " << x << "," << y;
    }
  EXPECT_GT(reflected, 20);
  EXPECT_GT(orange_concrete, orange_abstract + 20) << "concrete shows the object's bands";
}

TEST(PovgenRender, SubmergedObjectMovesWhenTheIorChangesAndKeepsItsOutline) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(5, 3.0, [](double, double) { return 0.0; }));
  write_obj(dir / "stone.obj", make_sphere(Vec3(0.6, -0.7, 0), 0.35, 16, 32));
  struct Seen {
    double x = 0, y = 0;
    int count = 0, black = 0;
  };
  auto render = [&](const char* ior) {
    const Image img = render_scene(
        dir, std::string("ior") + ior,
        std::vector<std::string>{
            "--water", (dir / "water.obj").string(), "--object", (dir / "stone.obj").string(),
            "--set", "object.0.color=" + color(kObject), "--set", "camera.location=[0, 2.5, 4]",
            "--set", "camera.look_at=[0, -0.5, 0]", "--set", "render.width=64", "--set",
            "render.height=48", "--set", "outline.units=world", "--set", "outline.width=0.04"} +
            opaque_flat_water() +
            std::vector<std::string>{"--set", "water.transmit=0.8", "--set",
                                     std::string("water.ior=") + ior});
    Seen s;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const Rgb8 c = img.at(x, y);
        const bool stone = c[0] > c[2] + 50;
        if (stone) s.x += x, s.y += y, ++s.count;
        // The outline seen through the water: black under a fifth of the water's colour, far
        // darker than the water over the white background (sums near 700 in the sRGB PNG).
        s.black += !stone && c[0] + c[1] + c[2] < 400;
      }
    s.x /= std::max(1, s.count), s.y /= std::max(1, s.count);
    return s;
  };
  const Seen air = render("1.0"), water = render("1.33");
  ASSERT_GT(air.count, 15);
  ASSERT_GT(water.count, 15);
  EXPECT_GT(std::hypot(air.x - water.x, air.y - water.y), 1.5)
      << "centroid " << air.x << "," << air.y << " vs " << water.x << "," << water.y;
  EXPECT_GT(water.black, 5) << "the outline survives refraction";
}

// A see-through closed tank of water is a see-through free surface over an opaque body: nothing
// behind the tank shows through its walls, and the outline shell does not paint the water in
// the line colour (rays refracted through the surface end on the floor and walls).
TEST(PovgenRender, TransparentClosedWaterHasAnOpaqueBodyAndIsNotDarkenedByItsShell) {
  ScratchDir dir;
  write_obj(dir / "tank.obj", water_box());
  const Image img = render_scene(
      dir, "tank",
      std::vector<std::string>{
          "--water", (dir / "tank.obj").string(), "--set", "camera.location=[0, 2, 3.5]", "--set",
          "camera.look_at=[0, -0.2, 0]", "--set", "render.width=64", "--set", "render.height=48"} +
          opaque_flat_water() +
          std::vector<std::string>{"--set", "water.transmit=0.9", "--set",
                                   "render.background=[1, 0, 0]"});
  int water = 0, dark = 0, see_through = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb8 c = img.at(x, y);
      if (near(c, {255, 0, 0}, 2)) continue;
      ++water;
      dark += c[0] + c[1] + c[2] < 60;
      see_through += c[0] > c[2] + 40;  // the red background mixed in
    }
  ASSERT_GT(water, 300);
  EXPECT_LT(dark, water / 5) << dark << " of " << water << " water pixels in the line colour";
  EXPECT_GT(dark, 0) << "the tank's rim is outlined";
  EXPECT_EQ(see_through, 0) << "the background shows through the tank";
}

// Where a wave meets the glass of a real tank (the Mantaflow dam break, ../shared/data, skipped
// where absent), the edge between the opaque body and the see-through free surface is a smooth
// curve, not the teeth of the marching-cubes faces' steps along the wall. The body's textures are
// painted pure green after povgen, so that the rendered green is the body: along the body's top
// edge, seen from povgen's camera at 640×360, at most 5 % of the columns stand more than 2 px off
// the chord of the columns 2 px either side. (The faces classified each by its own normal made
// 49–66 such teeth in frames 28–31, against 12–19.)
TEST(PovgenRender, TheWaterBodysEdgeAlongATanksGlassIsSmooth) {
  const fs::path shared = shared_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/data is absent: real-data test skipped";
  const fs::path data = shared / "data" / "mantaflow-dambreak";
  ScratchDir dir;
  for (const char* frame : {"0029", "0031"}) {
    SCOPED_TRACE(frame);
    const fs::path out = dir / frame;
    const CommandResult r = run_toonwater(
        {"povgen", "--out", out.string(), "--up", "z", "--water",
         (data / ("water_" + std::string(frame) + ".obj")).string(), "--set", "render.width=640",
         "--set", "render.height=360", "--set", "render.antialias=false"});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    const std::string meshes = "// Meshes of the current frame";
    std::string scene = read_text(out / "scene.pov");
    const std::size_t at = scene.find(meshes);
    ASSERT_NE(at, std::string::npos);
    scene.insert(at,
                 "#declare Water_body_texture = texture { pigment { rgb <0, 1, 0> }\n"
                 "  finish { emission 1 diffuse 0 ambient 0 } }\n"
                 "#declare Water_body_two_band_texture = Water_body_texture\n");
    write_text(out / "scene.pov", scene);
    const Povray p = run_povray(out);
    ASSERT_EQ(p.exit_code, 0) << p.output;
    const Image img = read_image(out / "frame.png");
    auto body = [&](int x, int y) { return near(img.at(x, y), {0, 255, 0}, 8); };
    // Per column, the top of the body's run up from its lowest pixel (the glass's bottom).
    std::vector<int> top(img.width, -1);
    int body_pixels = 0;
    for (int x = 0; x < img.width; ++x) {
      int y = img.height - 1;
      while (y >= 0 && !body(x, y)) --y;
      while (y > 0 && body(x, y - 1)) --y;
      top[x] = y;
      for (int v = 0; v < img.height; ++v) body_pixels += body(x, v);
    }
    int columns = 0, teeth = 0;
    for (int x = 2; x + 2 < img.width; ++x) {
      if (top[x - 2] < 0 || top[x] < 0 || top[x + 2] < 0) continue;
      ++columns;
      teeth += std::abs(top[x] - 0.5 * (top[x - 2] + top[x + 2])) > 2.0;
    }
    std::printf("frame %s: %d body pixels, %d teeth in %d columns\n", frame, body_pixels, teeth,
                columns);
    ASSERT_GT(columns, img.width / 2) << "the glass is seen below the water";
    EXPECT_GT(body_pixels, img.width * img.height / 10);
    EXPECT_LE(teeth, 0.05 * columns);
  }
}

TEST(PovgenRender, RidgeColourOnABumpAndNotOnFlatWater) {
  ScratchDir dir;
  write_obj(dir / "bump.obj", make_height_grid(61, 1.0, [](double x, double z) {
              return 0.25 * std::exp(-(x * x + z * z) / 0.05);
            }));
  write_obj(dir / "flat.obj", make_height_grid(61, 1.0, [](double, double) { return 0.0; }));
  auto args = [&](const char* mesh) {
    return std::vector<std::string>{"--water", (dir / mesh).string(),
                                    "--set",   "flow.ridge_color=[1, 0, 0]",
                                    "--set",   "flow.valley_color=[0, 0, 1]",
                                    "--set",   "water.bright=[0.6, 0.9, 0.6]",
                                    "--set",   "water.medium=[0.3, 0.7, 0.3]",
                                    "--set",   "water.dark=[0.1, 0.4, 0.1]",
                                    "--set",   "camera.location=[0, 2.5, 2.5]",
                                    "--set",   "camera.look_at=[0, 0, 0]",
                                    "--set",   "render.width=64",
                                    "--set",   "render.height=48"} +
           opaque_flat_water() + std::vector<std::string>{"--set", "flow.enabled=true"};
  };
  auto count_ridge = [](const Image& img) {
    int n = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) n += near(img.at(x, y), {255, 0, 0}, 2);
    return n;
  };
  EXPECT_GT(count_ridge(render_scene(dir, "bump", args("bump.obj"))), 5);
  EXPECT_EQ(count_ridge(render_scene(dir, "flat", args("flat.obj"))), 0);
}

// Input axes map to POV-Ray without mirroring: a marker on the viewer's right stays there.
TEST(PovgenRender, AxesAreMappedWithoutMirroring) {
  struct Case {
    const char* up;
    Vec3 marker;
    const char* camera;
  };
  const Case cases[] = {{"y", {0.8, 0.3, 0}, "[0, 2, 5]"},
                        {"z", {0.8, 0, 0.3}, "[0, -5, 2]"},
                        {"x", {0.3, 0.8, 0}, "[2, 0, -5]"}};
  for (const Case& c : cases) {
    ScratchDir dir;
    TriangleMesh water = make_height_grid(3, 2.0, [](double, double) { return 0.0; });
    Vec3 up = Vec3::Zero();
    up[c.up[0] - 'x'] = 1;
    for (Vec3& p : water.positions)  // the y-up grid turned so that its normal is `up`
      p = c.up[0] == 'y'   ? p
          : c.up[0] == 'z' ? Vec3(p.x(), -p.z(), p.y())
                           : Vec3(p.y(), p.z(), p.x());
    write_obj(dir / "water.obj", water);
    write_obj(dir / "marker.obj", make_sphere(c.marker, 0.25, 8, 16));
    const Image img = render_scene(
        dir, "axes",
        std::vector<std::string>{"--water", (dir / "water.obj").string(), "--object",
                                 (dir / "marker.obj").string(), "--up", c.up, "--set",
                                 "object.0.color=" + color(kObject), "--set",
                                 std::string("camera.location=") + c.camera, "--set",
                                 "camera.look_at=[0, 0, 0]", "--set", "render.width=64", "--set",
                                 "render.height=48", "--set", "outline.enabled=false"} +
            opaque_flat_water());
    double sum = 0;
    int count = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        if (orange(img.at(x, y))) sum += x, ++count;
    ASSERT_GT(count, 5) << "--up " << c.up;
    EXPECT_GT(sum / count, img.width / 2.0 + 5) << "--up " << c.up << ": marker mirrored";
  }
}

TEST(PovgenRender, TwoFrameSequenceRendersWithOnePovrayCommandAndWithRender) {
  ScratchDir dir;
  for (int f = 1; f <= 2; ++f)
    write_obj(dir / ("water_000" + std::to_string(f) + ".obj"),
              make_height_grid(21, 1.0, [f](double x, double z) {
                return 0.2 * std::sin(3 * x + f) * std::cos(2 * z);
              }));
  const fs::path out = dir / "seq";
  CommandResult r = run_toonwater({"povgen", "--water", (dir / "water_####.obj").string(), "--out",
                                   out.string(), "--set", "render.width=48", "--set",
                                   "render.height=36", "--set", "render.antialias=false"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("frame 2/2"), std::string::npos) << "progress shown";
  const Povray p = run_povray(out);
  ASSERT_EQ(p.exit_code, 0) << p.output;
  const Image a = read_image(out / "frame_1.png"), b = read_image(out / "frame_2.png");
  EXPECT_NE(a.pixels, b.pixels) << "the two frames show different meshes";

  fs::remove(out / "frame_1.png");
  fs::remove(out / "frame_2.png");
  r = run_toonwater({"render", out.string(), "--jobs", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 frame(s) rendered, 0 skipped (already rendered), 0 failed"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(fs::exists(out / "frame_1.png") && fs::exists(out / "frame_2.png"));

  // A broken frame is reported with POV-Ray's own message; the other frame still renders
  // (--force: both have their image from the run before).
  write_text(out / "water_0002.inc", "#declare Water_mesh = mesh2 { vertex_vectors { 1, <0,0,0> }");
  r = run_toonwater({"render", out.string(), "--jobs", "2", "--force"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("frame 2 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("rror"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("1 frame(s) rendered, 0 skipped (already rendered), 1 failed"),
            std::string::npos)
      << r.output;
}

TEST(PovgenRender, MantaflowWakeSequence) {
  const fs::path shared = shared_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/data is absent: skipping the Mantaflow sequence";
  const fs::path data = shared / "data" / "mantaflow-wake";
  ScratchDir dir;
  const fs::path out = dir / "wake";
  const CommandResult r =
      run_toonwater({"povgen", "--water", (data / "water_####.obj").string(), "--object",
                     (data / "sphere_####.obj").string(), "--up", "z", "--out", out.string(),
                     "--set", "render.frames=14-15", "--set", "render.width=64", "--set",
                     "render.height=48", "--set", "render.antialias=false"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const Povray p = run_povray(out);
  ASSERT_EQ(p.exit_code, 0) << p.output;
  EXPECT_EQ(p.output.find("Max Level: 10/10"), std::string::npos) << "ran out of trace depth";
  for (const char* frame : {"frame_14.png", "frame_15.png"}) {
    const Image img = read_image(out / frame);
    int object = 0, outline = 0, watery = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const Rgb8 c = img.at(x, y);
        object += orange(c);
        outline += c[0] + c[1] + c[2] < 60;  // water and sphere silhouettes
        watery += c[2] > c[0] + 40;
      }
    EXPECT_GT(object, 0) << frame << ": the sphere is visible";
    EXPECT_GT(outline, 10) << frame << ": outlines drawn";
    EXPECT_GT(watery, 100) << frame << ": water bands drawn";
  }
}

// water.shading = "mean" | "gaussian": the water coloured by its curvature with the curvature
// maps' diverging colour map, from the scene's camera — a view of surfaces that are not height
// fields. A sphere's H is the same everywhere, so at the sequence's 98th percentile range every
// water pixel is the colour map's positive end; a saddle's K < 0 shows blue.
TEST(PovgenRender, CurvatureViewUsesTheMapsColours) {
  ScratchDir dir;
  write_obj(dir / "ball.obj", make_sphere(Vec3::Zero(), 1.0, 24, 48));
  const std::vector<std::string> plain{
      "--set", "render.width=48",        "--set", "render.height=36",
      "--set", "render.antialias=false", "--set", "render.background=[1,1,1]",
      "--set", "outline.enabled=false"};
  const Image mean = render_scene(dir, "mean",
                                  std::vector<std::string>{"--water", (dir / "ball.obj").string(),
                                                           "--set", "water.shading=mean"} +
                                      plain);
  const toonwater::Rgb8 end = diverging_colour(1.0);
  const Rgb8 positive_end{end[0], end[1], end[2]};
  int ball = 0, at_end = 0;
  for (int y = 0; y < mean.height; ++y)
    for (int x = 0; x < mean.width; ++x) {
      const Rgb8 c = mean.at(x, y);
      if (near(c, to_rgb8(1, 1, 1), 2)) continue;
      ++ball;
      at_end += near(c, positive_end, 3);
    }
  ASSERT_GT(ball, 100);
  EXPECT_GT(at_end, ball * 9 / 10);
  const std::string pov = read_text(dir / "mean" / "scene.pov");
  EXPECT_EQ(pov.find("Toon_bands"), std::string::npos) << "a view draws no bands";
  EXPECT_EQ(pov.find("interior"), std::string::npos) << "nor refraction";

  write_obj(dir / "saddle.obj",
            make_height_grid(31, 1.0, [](double x, double z) { return 0.3 * (x * x - z * z); }));
  const Image gaussian = render_scene(
      dir, "gaussian",
      std::vector<std::string>{"--water", (dir / "saddle.obj").string(), "--set",
                               "water.shading=gaussian", "--set", "camera.location=[0, 3, 0.01]",
                               "--set", "camera.look_at=[0, 0, 0]"} +
          plain);
  const Rgb8 centre = gaussian.at(gaussian.width / 2, gaussian.height / 2);
  EXPECT_GT(centre[2], centre[0] + 40) << "K < 0 is blue";
}

}  // namespace
}  // namespace toonwater::test
