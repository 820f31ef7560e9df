// The outline shell's invisible front (templates/toon.inc, Toon_outline_shell) lights nothing:
// `diffuse 0 ambient 0` spares POV-Ray the light loop at every front a ray passes and changes
// no pixel, as those terms are weighted by 1 − transmit = 0. Checked where rays are deep: the
// refraction example (a clear body with an outlined object inside it, refraction, reflection
// and highlights) rendered by POV-Ray with the template's shell and with the shell's front given
// POV-Ray's default finish, which lights it; every pixel must be the same.
#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <string_view>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kUnlitFront =
    "texture { pigment { rgbt 1 } finish { diffuse 0 ambient 0 } }";
constexpr std::string_view kLitFront = "texture { pigment { rgbt 1 } }";

TEST(ShellFrontFinish, LightsNothingAndLeavesEveryPixelAsItWas) {
  ScratchDir dir;
  CommandResult r = run_toonwater({"simulate", "refraction", "--frames", "1", "--resolution", "64",
                                   "--out", (dir / "sim").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The config beside sim/, where its relative mesh paths point.
  const fs::path config = dir / "scene.toml";
  write_text(config, read_text(fs::path(TOONWATER_SOURCE_DIR) / "examples/refraction/scene.toml"));
  const fs::path unlit = dir / "unlit";
  r = run_toonwater({"povgen", "--config", config.string(), "--water",
                     (dir / "sim" / "water_####.obj").string(), "--set", "render.width=160",
                     "--set", "render.height=90", "--out", unlit.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string scene = read_text(unlit / "scene.pov");
  ASSERT_NE(scene.find("Toon_outline_shell(Obj_bones_shell"), std::string::npos) << scene;
  ASSERT_NE(scene.find("interior { ior"), std::string::npos) << "the water refracts";
  ASSERT_NE(scene.find("light_source"), std::string::npos) << "highlights need the light";

  // The same scene, its shells' fronts lit by POV-Ray's default finish.
  const fs::path lit = dir / "lit";
  fs::copy(unlit, lit);
  std::string toon = read_text(lit / "toon.inc");
  const std::size_t at = toon.find(kUnlitFront);
  ASSERT_NE(at, std::string::npos) << "the shell's front has no finish of its own";
  toon.replace(at, kUnlitFront.size(), kLitFront);
  write_text(lit / "toon.inc", toon);

  for (const fs::path& d : {unlit, lit}) {
    const Povray p = run_povray(d);
    ASSERT_EQ(p.exit_code, 0) << p.output;
  }
  const Image a = read_image(unlit / "frame.png");
  const Image b = read_image(lit / "frame.png");
  ASSERT_EQ(a.width, 160);
  ASSERT_EQ(b.width, a.width);
  ASSERT_EQ(b.height, a.height);
  std::size_t differing = 0, dark = 0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      if (a.at(x, y) != b.at(x, y)) ++differing;
      if (near(a.at(x, y), {0, 0, 0}, 8)) ++dark;
    }
  EXPECT_EQ(differing, 0u);
  EXPECT_GT(dark, 50u) << "the water's outline is drawn";
}

}  // namespace
}  // namespace toonwater::test
