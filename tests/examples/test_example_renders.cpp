// Each example rendered at 96×54 (two frames), its images checked for the feature it shows.
// The examples' own configs are used, with a few --set overrides that make a feature easy to
// find in the pixels (e.g. a magenta ridge colour).
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <set>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

struct Picture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
  const std::uint8_t* at(int x, int y) const {
    return &rgb[3 * (static_cast<std::size_t>(y) * width + x)];
  }
};

Picture load(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) {
    ADD_FAILURE() << "cannot read " << path;
    return {};
  }
  const OIIO::ImageSpec& spec = in->spec();
  Picture p{spec.width, spec.height, {}};
  p.rgb.resize(3 * static_cast<std::size_t>(p.width) * p.height);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, p.rgb.data());
  return p;
}

using PixelTest = std::function<bool(const std::uint8_t*)>;
const PixelTest warm = [](const std::uint8_t* c) { return c[0] > c[1] + 30 && c[0] > c[2] + 70; };
const PixelTest magenta = [](const std::uint8_t* c) {
  return c[0] > c[1] + 60 && c[2] > c[1] + 60;
};

struct Mask {
  int width = 0, height = 0;
  std::vector<bool> on;
  std::size_t count() const {
    return static_cast<std::size_t>(std::count(on.begin(), on.end(), true));
  }
  double mean_x() const {
    double sum = 0;
    for (std::size_t i = 0; i < on.size(); ++i)
      if (on[i]) sum += static_cast<double>(i % static_cast<std::size_t>(width));
    return sum / static_cast<double>(std::max<std::size_t>(count(), 1));
  }
};

Mask select(const Picture& p, const PixelTest& test) {
  Mask m{p.width, p.height, std::vector<bool>(static_cast<std::size_t>(p.width) * p.height)};
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x)
      m.on[static_cast<std::size_t>(y) * p.width + x] = test(p.at(x, y));
  return m;
}

// Pixels where two renders of the same view differ visibly.
Mask differing(const Picture& a, const Picture& b) {
  Mask m{a.width, a.height, std::vector<bool>(a.rgb.size() / 3)};
  for (std::size_t i = 0; i < m.on.size(); ++i)
    for (int k = 0; k < 3; ++k)
      if (std::abs(int(a.rgb[3 * i + k]) - int(b.rgb[3 * i + k])) > 30) m.on[i] = true;
  return m;
}

// simulate → povgen (the example's config, copied beside sim/) → render, in `dir`.
class Example {
 public:
  Example(const std::string& example, const std::string& scenario, int resolution)
      : example_(example) {
    const auto r = run_toonwater({"simulate", scenario, "--frames", "2", "--resolution",
                                  std::to_string(resolution), "--out", (dir_ / "sim").string()});
    EXPECT_EQ(r.exit_code, 0) << r.output;
  }

  // Renders frames first–last into DIR/name and returns the frame images' paths.
  std::vector<fs::path> render(const std::string& name, std::vector<std::string> sets,
                               bool objects = true, int first = 1, int last = 2) {
    std::string config = read_text(fs::path(TOONWATER_EXAMPLES_DIR) / example_ / "scene.toml");
    if (!objects)
      config.erase(config.find("[[object]]"), config.find("[render]") - config.find("[[object]]"));
    const fs::path config_path = dir_ / (name + ".toml");
    write_text(config_path, config);
    std::vector<std::string> args{"povgen",
                                  "--config",
                                  config_path.string(),
                                  "--water",
                                  (dir_ / "sim" / "water_####.obj").string(),
                                  "--out",
                                  (dir_ / name).string()};
    sets.insert(sets.end(), {"render.width=96", "render.height=54", "render.antialias=false"});
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    auto r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    r = run_toonwater({"render", (dir_ / name).string(), "--frames",
                       std::to_string(first) + "-" + std::to_string(last)});
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::vector<fs::path> frames;
    for (int f = first; f <= last; ++f)
      frames.push_back(dir_ / name / ("frame_" + std::to_string(f) + ".png"));
    return frames;
  }

 private:
  std::string example_;
  ScratchDir dir_;
};

// The sphere crosses the picture left to right and the ridges of its wake trail behind it.
TEST(ExampleRenders, WakeFollowsTheSphere) {
  Example wake("wake", "wake", 64);
  const auto frames = wake.render("scene", {"flow.ridge_color=[1,0,1]", "water.transmit=0"});
  const Picture first = load(frames[0]), last = load(frames[1]);
  const Mask sphere_first = select(first, warm), sphere_last = select(last, warm);
  ASSERT_GT(sphere_first.count(), 10u);
  ASSERT_GT(sphere_last.count(), 10u);
  EXPECT_GT(sphere_last.mean_x() - sphere_first.mean_x(), 0.3 * first.width);
  const Mask ridges = select(last, magenta);
  ASSERT_GT(ridges.count(), 10u);
  EXPECT_LT(ridges.mean_x(), sphere_last.mean_x());  // behind the sphere
}

// Before the ball lands the pool is calm; afterwards ridges ring the impact, symmetric about
// the camera's vertical plane through it. The two frames are the whole fall apart, so flow
// coherence, which would fade the new ripples in over a few frames of an animation, is off.
TEST(ExampleRenders, DropSendsOutRings) {
  Example drop("drop", "drop", 64);
  const auto frames = drop.render(
      "scene", {"flow.ridge_color=[1,0,1]", "water.transmit=0", "flow.coherence=false"});
  const Picture before = load(frames[0]), after = load(frames[1]);
  EXPECT_EQ(select(before, magenta).count(), 0u);
  const Mask rings = select(after, magenta);
  ASSERT_GT(rings.count(), 20u);
  std::size_t mirrored = 0;
  for (int y = 0; y < rings.height; ++y)
    for (int x = 0; x < rings.width; ++x) {
      const auto at = [&](int u) {
        return rings.on[static_cast<std::size_t>(y) * rings.width + u];
      };
      if (at(x) && (at(rings.width - 1 - x) || (x > 0 && at(rings.width - x)) ||
                    (x + 2 < rings.width && at(rings.width - 2 - x))))
        ++mirrored;
    }
  EXPECT_GT(static_cast<double>(mirrored), 0.7 * static_cast<double>(rings.count()));
  // A ring, not a blob: ridge pixels on both sides of the ball, far apart.
  EXPECT_LT(rings.mean_x(), 0.6 * rings.width);
  EXPECT_GT(rings.mean_x(), 0.4 * rings.width);
}

// The bones are seen through the water, and refraction moves them: their image changes with
// the water's ior.
TEST(ExampleRenders, RefractionShowsAndBendsTheBones) {
  Example fish("refraction", "refraction", 48);
  const auto with_bones = fish.render("bones", {});
  const auto no_bones = fish.render("water_only", {}, false, 1, 1);
  const auto flat_bones = fish.render("bones_ior1", {"water.ior=1.0"}, true, 1, 1);
  const auto flat_water = fish.render("water_only_ior1", {"water.ior=1.0"}, false, 1, 1);
  const Mask bent = differing(load(with_bones[0]), load(no_bones[0]));
  const Mask straight = differing(load(flat_bones[0]), load(flat_water[0]));
  ASSERT_GT(bent.count(), 30u) << "the bones are not visible through the water";
  ASSERT_GT(straight.count(), 30u);
  std::size_t moved = 0;
  for (std::size_t i = 0; i < bent.on.size(); ++i) moved += bent.on[i] != straight.on[i];
  EXPECT_GT(static_cast<double>(moved), 0.25 * static_cast<double>(bent.count()));
  // The body's waves move: the two frames differ.
  EXPECT_GT(differing(load(with_bones[0]), load(with_bones[1])).count(), 20u);
}

// The two balls hang symmetrically left and right of the camera. Where the water reflects them,
// the concrete reflection (left) adds the ball's own colours to the water — the orange of its
// underside — and the abstract one (right) only the flat silhouette: a single colour, and
// compared with its mirror image on the left, no orange.
TEST(ExampleRenders, ConcreteAndAbstractReflectionsDiffer) {
  Example pool("reflection", "reflection", 48);
  const Picture both = load(pool.render("scene", {}, true, 1, 1)[0]);
  const Picture none = load(
      pool.render("none", {"object.0.reflection=none", "object.1.reflection=none"}, true, 1, 1)[0]);
  const Mask reflected = differing(both, none);
  const auto on = [&](int x, int y) {
    return reflected.on[static_cast<std::size_t>(y) * both.width + x];
  };
  std::size_t left = 0, right = 0, pairs = 0;
  double warmer = 0;  // concrete minus abstract, red minus blue, summed over mirrored pairs
  std::set<std::array<int, 3>> right_colours;
  for (int y = 0; y < both.height; ++y)
    for (int x = 0; x < both.width; ++x) {
      if (!on(x, y)) continue;
      if (x >= both.width / 2) {
        ++right;
        const std::uint8_t* c = both.at(x, y);
        right_colours.insert({c[0] / 8, c[1] / 8, c[2] / 8});
        continue;
      }
      ++left;
      const int mirror = both.width - 1 - x;
      if (!on(mirror, y)) continue;
      const std::uint8_t *concrete = both.at(x, y), *abstract = both.at(mirror, y);
      warmer += (int(concrete[0]) - int(abstract[0])) - (int(concrete[2]) - int(abstract[2]));
      ++pairs;
    }
  ASSERT_GT(left, 10u) << "no concrete reflection in the water";
  ASSERT_GT(right, 10u) << "no abstract reflection in the water";
  ASSERT_GT(pairs, left / 2) << "the reflections should sit mirror-symmetrically";
  EXPECT_GT(warmer / static_cast<double>(pairs), 15.0)
      << "the concrete reflection should carry the ball's orange, the abstract one not";
  EXPECT_LE(right_colours.size(), 3u) << "the abstract reflection should be one flat colour";
}

// The documented commands on Blender Mantaflow output (Z up, closed liquid volume).
TEST(ExampleRenders, RealSimulationShowsSphereAndBowWave) {
  const fs::path data = shared_dir() / "data" / "mantaflow-wake";
  if (shared_dir().empty() || !fs::exists(data / "water_0020.obj"))
    GTEST_SKIP() << "../shared/data/mantaflow-wake is absent";
  ScratchDir dir;
  auto r =
      run_toonwater({"povgen",
                     "--up",
                     "z",
                     "--config",
                     (fs::path(TOONWATER_EXAMPLES_DIR) / "real-simulation" / "scene.toml").string(),
                     "--water",
                     (data / "water_####.obj").string(),
                     "--object",
                     (data / "sphere_####.obj").string(),
                     "--set",
                     "object.0.color=[0.92,0.45,0.18]",
                     "--set",
                     "flow.ridge_color=[1,0,1]",
                     "--set",
                     "render.frames=\"20-21\"",
                     "--set",
                     "render.width=144",
                     "--set",
                     "render.height=81",
                     "--set",
                     "render.antialias=false",
                     "--out",
                     (dir / "scene").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = run_toonwater({"render", (dir / "scene").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The bow wave's ridge is about 25 pixels at this size; at 96 × 54 it is two pixels across,
  // and whether any pixel's centre falls on it depends on a fraction of a cell.
  const Picture frame = load(dir / "scene" / "frame_21.png");
  EXPECT_GT(select(frame, warm).count(), 5u) << "the sphere should be visible";
  EXPECT_GT(select(frame, magenta).count(), 5u) << "the bow wave should carry ridge regions";
}

}  // namespace
}  // namespace toonwater::test
