// The default look on real simulation output: Blender Mantaflow's wake sequence from
// ../shared/data (a closed liquid volume with a half-submerged sphere, Z up; skipped where it
// is absent), written by povgen with nothing configured but the picture size, rendered at
// 480×270 without antialiasing and read back pixel by pixel.
#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr int kLookWidth = 480, kLookHeight = 270;

fs::path wake_dir() {
  const fs::path shared = shared_dir();
  return shared.empty() ? fs::path{} : shared / "data" / "mantaflow-wake";
}

std::vector<std::string> small_picture() {
  return {"--set", "render.width=" + std::to_string(kLookWidth),
          "--set", "render.height=" + std::to_string(kLookHeight),
          "--set", "render.antialias=false"};
}

void povgen(const fs::path& out, const std::string& water, const std::string& object,
            std::vector<std::string> extra) {
  std::vector<std::string> args{"povgen",   "--up", "z",     "--water",   water,
                                "--object", object, "--out", out.string()};
  args.insert(args.end(), extra.begin(), extra.end());
  const CommandResult r = run_toonwater(args);
  ASSERT_EQ(r.exit_code, 0) << r.output;
}

Image render(const fs::path& dir, const std::string& extra, const std::string& png) {
  const Povray p = run_povray(dir, extra);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  return read_image(dir / png);
}

// CIE L*a*b* of an sRGB colour (D65), and the CIE76 difference.
std::array<double, 3> lab(const Rgb8& c) {
  auto linear = [](int v) {
    const double s = v / 255.0;
    return s <= 0.04045 ? s / 12.92 : std::pow((s + 0.055) / 1.055, 2.4);
  };
  const double r = linear(c[0]), g = linear(c[1]), b = linear(c[2]);
  const double x = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047;
  const double y = 0.2126 * r + 0.7152 * g + 0.0722 * b;
  const double z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116.0; };
  return {116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))};
}

double delta_e(const Rgb8& a, const Rgb8& b) {
  const auto p = lab(a), q = lab(b);
  return std::hypot(p[0] - q[0], p[1] - q[1], p[2] - q[2]);
}

// The background is the pixel colour of the picture's corner (the scene never reaches it).
Rgb8 background(const Image& img) { return img.at(0, 0); }

// The camera povgen chose, in the input's axes (z up: POV-Ray's (x, y, z) is (x, z, y)).
std::string camera_setting(const fs::path& scene, const std::string& key) {
  std::ifstream in(scene / "scene.pov");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  std::smatch m;
  const std::regex re(key + " <([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)>");
  if (!std::regex_search(text, m, re)) return "";
  return "camera." + key + "=[" + m[1].str() + ", " + m[3].str() + ", " + m[2].str() + "]";
}

struct Look {
  double coverage = 0;      // share of the picture that is not background
  int edge_pixels = 0;      // scene pixels on the picture's border
  double main_delta_e = 0;  // most common scene colour against the background
  double top12 = 0;         // share of the scene's pixels in its 12 most common colours
};

Look measure(const Image& img) {
  Look look;
  const Rgb8 bg = background(img);
  std::map<Rgb8, int> counts;
  int scene = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const Rgb8 c = img.at(x, y);
      if (near(c, bg, 2)) continue;
      ++scene;
      ++counts[c];
      look.edge_pixels += x == 0 || y == 0 || x == img.width - 1 || y == img.height - 1;
    }
  look.coverage = double(scene) / (img.width * img.height);
  std::vector<std::pair<int, Rgb8>> by_count;
  for (const auto& [c, n] : counts) by_count.push_back({n, c});
  std::sort(by_count.rbegin(), by_count.rend());
  int top = 0;
  for (std::size_t i = 0; i < std::min<std::size_t>(12, by_count.size()); ++i)
    top += by_count[i].first;
  look.top12 = scene ? double(top) / scene : 0;
  look.main_delta_e = by_count.empty() ? 0 : delta_e(by_count[0].second, bg);
  return look;
}

// One test, so that ctest (a process per test) writes and renders the sequence once.
TEST(WakeDefaults, CartoonLookWithNothingConfigured) {
  const fs::path data = wake_dir();
  if (data.empty()) GTEST_SKIP() << "../shared/data is absent: real-data tests skipped";
  ScratchDir dir;
  // Every frame: the camera frames the whole sequence. Three frames are rendered.
  povgen(dir / "defaults", (data / "water_####.obj").string(), (data / "sphere_####.obj").string(),
         small_picture());
  std::map<int, Image> frames;
  for (int frame : {1, 9, 30}) {
    const std::string n = std::to_string(frame);
    frames[frame] = render(dir / "defaults", "+SF" + n + " +EF" + n,
                           "frame_" + std::string(n.size() < 2 ? "0" : "") + n + ".png");
  }

  // The camera frames the whole sequence and fills the picture.
  for (const auto& [frame, img] : frames) {
    ASSERT_EQ(img.width, kLookWidth);
    const Look look = measure(img);
    std::printf("frame %d: scene covers %.1f %% of the picture, %d scene pixels on its edge\n",
                frame, 100 * look.coverage, look.edge_pixels);
    EXPECT_EQ(look.edge_pixels, 0) << "frame " << frame << ": the scene is cut by the image edge";
    EXPECT_GE(look.coverage, 0.25) << "frame " << frame;
  }

  // The water stands out against the background and is made of flat colours.
  for (const auto& [frame, img] : frames) {
    const Look look = measure(img);
    std::printf(
        "frame %d: main colour dE %.1f from the background, %.1f %% of the scene in "
        "12 colours\n",
        frame, look.main_delta_e, 100 * look.top12);
    EXPECT_GE(look.main_delta_e, 25.0) << "frame " << frame;
    EXPECT_GE(look.top12, 0.85) << "frame " << frame;
  }

  // The sphere's silhouette where it is in air carries a line: the silhouette is the outline of
  // the sphere rendered alone (the water moved far below), in air where the sphere is seen in
  // the picture with opaque water; a line is a line-coloured pixel outside the sphere within
  // 2 px of it in the default picture.
  const std::string location = camera_setting(dir / "defaults", "location");
  const std::string look_at = camera_setting(dir / "defaults", "look_at");
  ASSERT_FALSE(location.empty() || look_at.empty());
  const std::vector<std::string> plain =
      small_picture() + std::vector<std::string>{"--set", location,
                                                 "--set", look_at,
                                                 "--set", "outline.enabled=false",
                                                 "--set", "water.transmit=0",
                                                 "--set", "water.reflection=0",
                                                 "--set", "object.0.color=[1, 0, 1]",
                                                 "--set", "render.frames=\"9\""};
  {
    std::ofstream low(dir / "low.obj");
    low << "v -9 -9 -5\nv 9 -9 -5\nv 0 9 -5\nf 1 2 3\n";
  }
  // A single file: no frame to pick (render.frames is refused for one).
  const std::vector<std::string> single(plain.begin(), plain.end() - 2);
  povgen(dir / "alone", (dir / "low.obj").string(), (data / "sphere_0009.obj").string(), single);
  povgen(dir / "opaque", (data / "water_####.obj").string(), (data / "sphere_####.obj").string(),
         plain);
  const Image alone = render(dir / "alone", "", "frame.png");
  const Image opaque = render(dir / "opaque", "", "frame.png");
  const Image& look = frames.at(9);
  auto magenta = [](const Rgb8& c) { return c[1] < 40 && c[0] > 40 && std::abs(c[0] - c[2]) < 30; };
  auto sphere = [&](int x, int y) {
    return x >= 0 && y >= 0 && x < kLookWidth && y < kLookHeight && magenta(alone.at(x, y));
  };
  int silhouette = 0, lined = 0;
  for (int y = 0; y < kLookHeight; ++y)
    for (int x = 0; x < kLookWidth; ++x) {
      if (!sphere(x, y) || !magenta(opaque.at(x, y))) continue;
      if (sphere(x - 1, y) && sphere(x + 1, y) && sphere(x, y - 1) && sphere(x, y + 1)) continue;
      ++silhouette;
      bool line = false;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const int u = std::clamp(x + dx, 0, kLookWidth - 1),
                    v = std::clamp(y + dy, 0, kLookHeight - 1);
          const Rgb8 c = look.at(u, v);
          line = line || (!sphere(u, v) && c[0] < 40 && c[1] < 40 && c[2] < 40);
        }
      lined += line;
    }
  std::printf("frame 9: %d of %d silhouette pixels in air carry a line (%.1f %%)\n", lined,
              silhouette, 100.0 * lined / std::max(1, silhouette));
  ASSERT_GT(silhouette, 30);
  EXPECT_GE(lined, 0.9 * silhouette);
}

}  // namespace
}  // namespace toonwater::test
