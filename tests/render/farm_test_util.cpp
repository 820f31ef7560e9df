#include "tests/render/farm_test_util.hpp"

#include <gtest/gtest.h>

namespace toonwater::test {

namespace fs = std::filesystem;

fs::path make_wake_scene(const ScratchDir& dir) {
  const CommandResult sim =
      run_toonwater({"simulate", "wake", "--frames", std::to_string(kFarmFrames), "--out",
                     (dir / "sim").string()});
  EXPECT_EQ(sim.exit_code, 0) << sim.output;
  // The config's mesh paths are relative to it: beside sim/, as scripts/demo.sh puts it.
  fs::copy_file(fs::path(TOONWATER_SOURCE_DIR) / "examples/wake/scene.toml", dir / "scene.toml");
  const CommandResult pov = run_toonwater(
      {"povgen", "--config", (dir / "scene.toml").string(), "--water",
       (dir / "sim/water_####.obj").string(), "--set", "render.width=" + std::to_string(kFarmWidth),
       "--set", "render.height=" + std::to_string(kFarmHeight), "--out", (dir / "scene").string()});
  EXPECT_EQ(pov.exit_code, 0) << pov.output;
  return dir / "scene";
}

fs::path render_locally(const ScratchDir& dir, const fs::path& scene) {
  const fs::path reference = dir / "reference";
  fs::copy(scene, reference, fs::copy_options::recursive);
  const CommandResult r = run_toonwater({"render", reference.string()});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  return reference;
}

std::string frame_name(int frame) { return "frame_" + std::to_string(frame) + ".png"; }

void expect_frames_like(const fs::path& scene, const fs::path& reference) {
  for (int f = 1; f <= kFarmFrames; ++f) {
    ASSERT_TRUE(fs::is_regular_file(scene / frame_name(f))) << "frame " << f << " missing";
    const Image image = read_image(scene / frame_name(f));
    const Image expected = read_image(reference / frame_name(f));
    ASSERT_EQ(image.width, kFarmWidth) << "frame " << f;
    ASSERT_EQ(image.height, kFarmHeight) << "frame " << f;
    EXPECT_EQ(image.pixels, expected.pixels) << "frame " << f << " differs from the local render";
  }
  for (const auto& entry : fs::directory_iterator(scene))
    EXPECT_EQ(entry.path().filename().string().find(".render-"), std::string::npos)
        << "left behind: " << entry.path();
}

void write_killing_povray(const fs::path& bin, const fs::path& marker) {
  fs::create_directories(bin);
  const std::string real = "/usr/bin/povray";
  write_text(bin / "povray",
             "#!/bin/sh\n"
             "if mkdir '" +
                 marker.string() +
                 "' 2>/dev/null; then\n"
                 "  " +
                 real +
                 " \"$@\" &\n"
                 "  sleep 0.5\n"
                 "  kill -KILL $PPID $!\n"
                 "  exit 137\n"
                 "fi\n"
                 "exec " +
                 real + " \"$@\"\n");
  fs::permissions(bin / "povray", fs::perms::owner_all | fs::perms::group_read |
                                      fs::perms::group_exec | fs::perms::others_read |
                                      fs::perms::others_exec);
}

}  // namespace toonwater::test
