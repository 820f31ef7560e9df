// Helpers for the render farm tests: the demo's wake scene at a small size, rendered locally as
// the reference, and a povray wrapper that kills the farm task running it (a fault).
#pragma once

#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <filesystem>
#include <string>

namespace toonwater::test {

inline constexpr int kFarmFrames = 6, kFarmWidth = 160, kFarmHeight = 90;

// The wake example (scripts/demo.sh) as a povgen scene: kFarmFrames frames at
// kFarmWidth × kFarmHeight in `dir`/scene. Returns the scene directory.
std::filesystem::path make_wake_scene(const ScratchDir& dir);

// A copy of the scene's directory with every frame rendered by the local `toonwater render`.
std::filesystem::path render_locally(const ScratchDir& dir, const std::filesystem::path& scene);

// POV-Ray's name for frame f (1-based) of the scene.
std::string frame_name(int frame);

// Checks that every frame of `scene` is a complete image equal, pixel for pixel, to the local
// render's, and that no temporary directory of a task was left behind.
void expect_frames_like(const std::filesystem::path& scene, const std::filesystem::path& reference);

// Writes `bin`/povray: the first time it runs (across processes: the directory `marker` is
// created), it starts the real POV-Ray, waits until it has been rendering for a moment, then kills
// the process that started it (the farm task) and POV-Ray with SIGKILL. Later runs are POV-Ray.
void write_killing_povray(const std::filesystem::path& bin, const std::filesystem::path& marker);

}  // namespace toonwater::test
