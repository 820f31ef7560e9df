// Outline shell culling (scene/shell_culling.hpp): on every example, reflection and refraction
// included, the scene written with the shell faces no ray can see left out renders exactly the
// pixels of the scene with every shell face, rendered by POV-Ray and read back; and faces are
// left out where the rule allows it (opaque water), none where the water refracts.
#include "scene/config.hpp"
#include "pipeline/generate_scene.hpp"
#include "scene/shell_culling.hpp"
#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;
using namespace toonwater;

struct ExampleCase {
  std::string example;   // examples/NAME
  std::string scenario;  // toonwater simulate SCENARIO; empty: ../shared/data/mantaflow-wake
  std::string set;       // an extra --set
};

class ShellCulling : public ::testing::TestWithParam<ExampleCase> {};

// The scene of the example's config at 160×90 (antialiased), with or without culling.
PovgenReport write_scene(const ExampleCase& c, const fs::path& config_file,
                         const std::string& water, const std::vector<std::string>& objects,
                         const fs::path& out, bool cull) {
  ConfigSources sources;
  sources.file = config_file;
  sources.object_patterns = objects;
  sources.overrides = {"render.width=160", "render.height=90"};
  if (c.scenario.empty()) sources.overrides.push_back("render.frames=\"20-21\"");
  if (!c.set.empty()) sources.overrides.push_back(c.set);
  const SceneConfig config = load_config(sources);
  PovgenRequest request;
  request.water_pattern = water;
  request.up = c.scenario.empty() ? Axis::z : Axis::y;
  request.out_dir = out;
  request.cull_shells = cull;
  return generate_scene(config, request, {}, nullptr);
}

TEST_P(ShellCulling, LeavesEveryPixelAsItWas) {
  const ExampleCase& c = GetParam();
  const fs::path example = fs::path(TOONWATER_SOURCE_DIR) / "examples" / c.example;
  ScratchDir dir;
  std::string water;
  std::vector<std::string> objects;
  if (c.scenario.empty()) {
    const fs::path data = shared_dir() / "data" / "mantaflow-wake";
    if (shared_dir().empty() || !fs::exists(data / "water_0020.obj"))
      GTEST_SKIP() << "../shared/data/mantaflow-wake is absent";
    water = (data / "water_####.obj").string();
    objects = {(data / "sphere_####.obj").string()};
  } else {
    const CommandResult r = run_toonwater({"simulate", c.scenario, "--frames", "2", "--resolution",
                                           "64", "--out", (dir / "sim").string()});
    ASSERT_EQ(r.exit_code, 0) << r.output;
    water = (dir / "sim" / "water_####.obj").string();
  }
  // The config beside sim/, where its relative mesh paths point.
  const fs::path config = dir / "scene.toml";
  write_text(config, read_text(example / "scene.toml"));

  const PovgenReport culled = write_scene(c, config, water, objects, dir / "culled", true);
  const PovgenReport full = write_scene(c, config, water, objects, dir / "full", false);
  ASSERT_GT(full.shell_faces, 0u);
  const SceneConfig loaded = [&] {
    ConfigSources s;
    s.file = config;
    s.object_patterns = objects;
    if (!c.set.empty()) s.overrides.push_back(c.set);
    return load_config(s);
  }();
  const bool culls = culled.shell_faces_kept < full.shell_faces_kept;
  if (loaded.water.transmit > 0)
    EXPECT_FALSE(culls) << "refracting water: nothing culled";
  else
    EXPECT_TRUE(culls) << "opaque water: faces culled";

  for (const fs::path& scene : {dir / "culled", dir / "full"}) {
    const Povray p = run_povray(scene);
    ASSERT_EQ(p.exit_code, 0) << p.output;
    // The proof's premise where faces are dropped: no ray ran out of trace depth (a dropped
    // face is one level less).
    if (culls) {
      EXPECT_EQ(p.output.find("Max Level: 10/10"), std::string::npos) << scene;
    }
  }
  std::size_t frames = 0;
  for (const auto& entry : fs::directory_iterator(dir / "full")) {
    if (entry.path().extension() != ".png") continue;
    const Image a = read_image(entry.path());
    const Image b = read_image(dir / "culled" / entry.path().filename());
    ASSERT_EQ(a.width, b.width);
    ASSERT_EQ(a.height, b.height);
    std::size_t differing = 0;
    std::string first;
    for (int y = 0; y < a.height; ++y)
      for (int x = 0; x < a.width; ++x)
        if (a.at(x, y) != b.at(x, y)) {
          if (differing++ == 0)
            first = "first at " + std::to_string(x) + "," + std::to_string(y) + ": " +
                    std::to_string(a.at(x, y)[0]) + " " + std::to_string(a.at(x, y)[1]) + " " +
                    std::to_string(a.at(x, y)[2]) + " unculled, " + std::to_string(b.at(x, y)[0]) +
                    " " + std::to_string(b.at(x, y)[1]) + " " + std::to_string(b.at(x, y)[2]) +
                    " culled";
        }
    EXPECT_EQ(differing, 0u) << entry.path().filename() << " " << first;
    ++frames;
  }
  EXPECT_EQ(frames, 2u);
}

INSTANTIATE_TEST_SUITE_P(
    Examples, ShellCulling,
    ::testing::Values(ExampleCase{"wake", "wake", ""}, ExampleCase{"drop", "drop", ""},
                      ExampleCase{"reflection", "reflection", ""},
                      ExampleCase{"refraction", "refraction", ""},
                      ExampleCase{"real-simulation", "", ""},
                      // Culled closed volumes, with an object inside and
                      // one crossing the surface:
                      ExampleCase{"refraction", "refraction", "water.transmit=0"},
                      ExampleCase{"real-simulation", "", "water.transmit=0"}),
    [](const ::testing::TestParamInfo<ExampleCase>& test) {
      std::string name = test.param.example + (test.param.set.empty() ? "" : "_opaque");
      for (char& ch : name)
        if (ch == '-') ch = '_';
      return name;
    });

// On a closed sphere seen from outside, the faces kept are those facing away from the eye (and
// their neighbours); all are kept when the shell lies too close to the sphere or an object's box
// covers it.
TEST(ShellCullingGeometry, KeepsTheFacesTheEyeSeesFromBehind) {
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 1.0, 24, 48);
  std::vector<Vec3> normals;
  for (const Vec3& p : sphere.positions) normals.push_back(p.normalized());
  const SceneMesh mesh = make_scene_mesh(sphere, normals, true, Axis::y);
  const std::vector<double> offsets(mesh.positions.size(), 0.01);
  const Vec3 eye(0, 0, -5);
  const std::vector<bool> kept = shell_faces_seen_from_behind(mesh, offsets, eye);
  std::size_t count = 0;
  for (std::size_t f = 0; f < kept.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Vec3 centre = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3;
    // Beyond the neighbours of the silhouette's faces (a ring spans 7.5°), the side is clear:
    // faces towards the eye go, the others stay.
    const double facing = centre.normalized().dot((eye - centre).normalized());
    if (facing > 0.4) {
      EXPECT_FALSE(kept[f]) << f;
    }
    if (facing < -0.1) {
      EXPECT_TRUE(kept[f]) << f;
    }
    count += kept[f];
  }
  // The eye, 5 radii away, sees a cap of 40 % of the sphere from the front.
  EXPECT_GT(count, kept.size() / 2);
  EXPECT_LT(count, kept.size() * 4 / 5);

  const auto all_kept = [](const std::vector<bool>& k) {
    return std::count(k.begin(), k.end(), true) == static_cast<std::ptrdiff_t>(k.size());
  };
  const std::vector<double> thin(mesh.positions.size(), 1e-5);
  EXPECT_TRUE(all_kept(shell_faces_seen_from_behind(mesh, thin, eye)));
  const KeepOutBox object{Vec3(-0.5, -0.5, -2), Vec3(0.5, 0.5, -1.005)};
  const std::vector<bool> beside = shell_faces_seen_from_behind(mesh, offsets, eye, {&object, 1});
  for (std::size_t f = 0; f < kept.size(); ++f) {
    const Triangle& t = mesh.triangles[f];
    const Vec3 centre = (mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3;
    if (centre.z() < -0.995 && std::abs(centre.x()) < 0.05 && std::abs(centre.y()) < 0.05) {
      EXPECT_TRUE(beside[f]) << "the face under the object's box is kept";
    }
  }
  EXPECT_GT(std::count(beside.begin(), beside.end(), true),
            std::count(kept.begin(), kept.end(), true));
}

// Which shells only camera rays meet (the premise of culling): none where the water refracts,
// whatever else holds; where it only reflects, the shells that reflected rays cannot see.
TEST(ShellCullingRule, OnlyWhereNoRefractedOrReflectedRayCanMeetTheShell) {
  SceneConfig config;
  config.water.shading = WaterShading::toon;
  config.water.transmit = 0.6;
  config.water.reflection = 0.0;
  EXPECT_FALSE(shell_met_by_camera_rays_only(config, true)) << "refracting";
  config.water.reflection = 0.3;
  EXPECT_FALSE(shell_met_by_camera_rays_only(config, true)) << "refracting and reflecting";
  config.water.transmit = 0;
  EXPECT_TRUE(shell_met_by_camera_rays_only(config, true)) << "reflecting, no_reflection shell";
  EXPECT_FALSE(shell_met_by_camera_rays_only(config, false)) << "reflecting, reflected shell";
  config.water.reflection = 0;
  EXPECT_TRUE(shell_met_by_camera_rays_only(config, false)) << "opaque, no reflection";
}

}  // namespace
}  // namespace toonwater::test
