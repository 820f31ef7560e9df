// Render farms without Slurm: frame ranges split into tasks, a range rendered in one POV-Ray
// process (what every farm task runs), and GNU parallel on this machine (`:` in the hosts file,
// no ssh). Images are compared pixel for pixel with the local `toonwater render`.
#include "tests/render/farm_test_util.hpp"

#include "render/farm.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

TEST(FarmTasks, ShellQuotingSurvivesTheShell) {
  ScratchDir dir;
  const std::string hostile = "a b'c\"$(touch " + (dir / "pwned").string() + ")";
  const std::string line =
      "printf %s " + shell_quote(hostile) + " > " + shell_quote((dir / "out").string());
  ASSERT_EQ(std::system(line.c_str()), 0);
  EXPECT_EQ(read_text(dir / "out"), hostile);
  EXPECT_FALSE(fs::exists(dir / "pwned"));
}

class FarmScene : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new ScratchDir;
    scene_ = make_wake_scene(*dir_);
  }
  static void TearDownTestSuite() { delete dir_; }
  // The local render, made when a test first compares with it.
  static const fs::path& reference() {
    if (reference_.empty()) reference_ = render_locally(*dir_, scene_);
    return reference_;
  }
  // A fresh copy of the unrendered scene.
  fs::path copy_scene(const std::string& name) const {
    const fs::path copy = work_ / name;
    fs::copy(scene_, copy, fs::copy_options::recursive);
    return copy;
  }
  static ScratchDir* dir_;
  static fs::path scene_, reference_;
  ScratchDir work_;
};
ScratchDir* FarmScene::dir_ = nullptr;
fs::path FarmScene::scene_, FarmScene::reference_;

TEST_F(FarmScene, RenderTaskRendersItsRangeInOneProcessLikeTheLocalRender) {
  const fs::path scene = copy_scene("task");
  const CommandResult r = run_toonwater({"render-task", scene.string(), "--frames", "2-4"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int f : {1, 5, 6}) EXPECT_FALSE(fs::exists(scene / frame_name(f))) << f;
  for (int f = 2; f <= 4; ++f)
    EXPECT_EQ(read_image(scene / frame_name(f)).pixels,
              read_image(reference() / frame_name(f)).pixels)
        << f;
}

TEST_F(FarmScene, RenderTaskReportsAFailedFrameAndRendersTheOthers) {
  const fs::path scene = copy_scene("broken");
  fs::remove(scene / "water_0003.inc");
  const CommandResult r = run_toonwater({"render-task", scene.string(), "--frames", "1-6"});
  EXPECT_EQ(r.exit_code, 5) << r.output;  // POV-Ray failed (README, "Exit codes")
  EXPECT_NE(r.output.find("frame 3 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("water_0003.inc"), std::string::npos) << r.output;  // POV-Ray's message
  EXPECT_FALSE(fs::exists(scene / frame_name(3)));
  EXPECT_TRUE(fs::exists(scene / "render_3.log"));
  for (int f : {1, 2, 4, 5, 6})
    EXPECT_EQ(read_image(scene / frame_name(f)).pixels,
              read_image(reference() / frame_name(f)).pixels)
        << f;
}

// Writes `bin`/povray, which appends its arguments to `log` and runs POV-Ray.
void write_logging_povray(const fs::path& bin, const fs::path& log) {
  fs::create_directories(bin);
  write_text(bin / "povray",
             "#!/bin/sh\necho \"$@\" >> '" + log.string() + "'\nexec /usr/bin/povray \"$@\"\n");
  fs::permissions(bin / "povray", fs::perms::owner_all);
}

// POV-Ray's front end gives up when its threads are slow to start on a loaded machine ("Timed
// out waiting for worker thread startup", nothing rendered): the same process is started again,
// a few times, before its frame counts as failed. Here POV-Ray's start times out twice for the
// run from frame 1, then works; then always for it: frame 1 fails after four tries, with
// POV-Ray's message, and a new process renders the rest.
TEST_F(FarmScene, APovrayWhoseThreadsDidNotStartIsStartedAgain) {
  const fs::path plain = copy_scene("plain");
  ASSERT_EQ(run_povray(plain).exit_code, 0);
  // POV-Ray's start from frame 1 times out as many times as bin/timeouts says; bin/tries
  // counts those starts.
  const fs::path bin = work_ / "bin", tries = bin / "tries";
  fs::create_directories(bin);
  write_text(bin / "povray",
             "#!/bin/sh\n"
             "here=$(dirname \"$0\")\n"
             "case \" $* \" in *\" +SF1 \"*)\n"
             "  n=$(($(cat \"$here/tries\" 2>/dev/null || echo 0) + 1))\n"
             "  echo $n > \"$here/tries\"\n"
             "  if [ $n -le $(cat \"$here/timeouts\") ]; then\n"
             "    echo 'povray: Timed out waiting for worker thread startup' >&2; exit 1\n"
             "  fi;;\n"
             "esac\n"
             "exec /usr/bin/povray \"$@\"\n");
  fs::permissions(bin / "povray", fs::perms::owner_all);
  auto time_out_starts = [&](int timeouts) {
    write_text(bin / "timeouts", std::to_string(timeouts) + "\n");
    fs::remove(tries);
  };
  const ScopedEnvironmentVariable path_variable = path_with_first(bin);

  time_out_starts(2);
  const fs::path scene = copy_scene("slow_start");
  CommandResult r = run_toonwater({"render", scene.string(), "--jobs", "1"});
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_text(tries), "3\n");
  expect_frames_like(scene, plain);

  time_out_starts(1000);
  const fs::path stuck = copy_scene("never_starts");
  r = run_toonwater({"render", stuck.string(), "--jobs", "1"});
  EXPECT_EQ(r.exit_code, 5) << r.output;
  EXPECT_NE(r.output.find("frame 1 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("Timed out waiting for worker thread startup"), std::string::npos)
      << r.output;
  EXPECT_EQ(read_text(tries), "4\n") << "one start and three more";
  EXPECT_FALSE(fs::exists(stuck / frame_name(1)));
  for (int f = 2; f <= kFarmFrames; ++f)
    EXPECT_EQ(read_image(stuck / frame_name(f)).pixels, read_image(plain / frame_name(f)).pixels)
        << f;
}

// The local render: one POV-Ray process per range of frames, the images those of plain
// `povray scene.ini`; a failed frame in a range is reported and a new process takes the rest.
TEST_F(FarmScene, LocalRenderRunsOneProcessPerRangeWithPovraysOwnImages) {
  const fs::path plain = copy_scene("plain");
  ASSERT_EQ(run_povray(plain).exit_code, 0);
  write_logging_povray(work_ / "bin", work_ / "runs.log");
  const ScopedEnvironmentVariable path_variable = path_with_first(work_ / "bin");

  const fs::path scene = copy_scene("ranges");
  CommandResult r = run_toonwater({"render", scene.string(), "--jobs", "3"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("6 frame(s) rendered, 0 skipped (already rendered), 0 failed"),
            std::string::npos)
      << r.output;
  std::string runs = read_text(work_ / "runs.log");
  EXPECT_EQ(std::count(runs.begin(), runs.end(), '\n'), 3) << runs;
  for (const char* range : {"+SF1 +EF2", "+SF3 +EF4", "+SF5 +EF6"})
    EXPECT_NE(runs.find(range), std::string::npos) << range << " in " << runs;
  expect_frames_like(scene, plain);

  const fs::path broken = copy_scene("broken_range");
  fs::remove(broken / "water_0002.inc");
  fs::remove(work_ / "runs.log");
  r = run_toonwater({"render", broken.string(), "--jobs", "2"});
  EXPECT_EQ(r.exit_code, 5) << r.output;
  EXPECT_NE(r.output.find("frame 2 failed"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("water_0002.inc"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("5 frame(s) rendered, 0 skipped (already rendered), 1 failed"),
            std::string::npos)
      << r.output;
  runs = read_text(work_ / "runs.log");
  EXPECT_NE(runs.find("+SF3 +EF3"), std::string::npos) << "a new process for frame 3: " << runs;
  EXPECT_FALSE(fs::exists(broken / frame_name(2)));
  for (int f : {1, 3, 4, 5, 6})
    EXPECT_EQ(read_image(broken / frame_name(f)).pixels, read_image(plain / frame_name(f)).pixels)
        << f;
}

TEST_F(FarmScene, ParallelOnThisMachineRendersEveryFrame) {
  const fs::path scene = copy_scene("parallel");
  write_text(work_ / "hosts", ":\n");
  const CommandResult r = run_toonwater({"render", scene.string(), "--on", "parallel", "--hosts",
                                         (work_ / "hosts").string(), "--frames-per-task", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_frames_like(scene, reference());
  EXPECT_NE(r.output.find("6 frame(s) rendered"), std::string::npos) << r.output;
  // One log per task, from the task itself.
  for (const char* range : {"1-2", "3-4", "5-6"})
    EXPECT_NE(read_text(scene / ".farm/parallel/1" / range / "stderr").find("render-task: frames"),
              std::string::npos)
        << range;
}

TEST_F(FarmScene, ParallelRetriesATaskKilledMidFrameAndLeavesNoPartialImage) {
  const fs::path scene = copy_scene("killed");
  write_text(work_ / "hosts", ":\n");
  reference();  // rendered before the faulty povray is on PATH
  write_killing_povray(work_ / "bin", work_ / "killed-once");
  const ScopedEnvironmentVariable path_variable = path_with_first(work_ / "bin");
  const CommandResult r = run_toonwater({"render", scene.string(), "--on", "parallel", "--hosts",
                                         (work_ / "hosts").string(), "--frames-per-task", "3"});
  ASSERT_TRUE(fs::exists(work_ / "killed-once"));  // the fault happened
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Without the retry the killed task's frames would be missing and the run would fail.
  expect_frames_like(scene, reference());
}

TEST_F(FarmScene, AHostGnuParallelCannotReachIsAnOutputFailureNamingIt) {
  const fs::path scene = copy_scene("unreachable");
  write_text(work_ / "hosts", "nosuchhost.invalid\n");
  const CommandResult r = run_toonwater({"render", scene.string(), "--on", "parallel", "--hosts",
                                         (work_ / "hosts").string(), "--frames-per-task", "3"});
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("could not run tasks on nosuchhost.invalid"), std::string::npos)
      << r.output;
}

TEST_F(FarmScene, FramesWithAnImageAreSkippedUnlessForced) {
  const fs::path scene = copy_scene("resume");
  for (int f : {1, 2, 3, 5}) fs::copy_file(reference() / frame_name(f), scene / frame_name(f));
  const auto before = fs::last_write_time(scene / frame_name(1));
  write_text(work_ / "hosts", ":\n");
  const CommandResult r = run_toonwater(
      {"render", scene.string(), "--on", "parallel", "--hosts", (work_ / "hosts").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 frame(s) rendered, 4 skipped"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(scene / frame_name(1)), before);
  expect_frames_like(scene, reference());
  const CommandResult forced = run_toonwater({"render", scene.string(), "--on", "parallel",
                                              "--hosts", (work_ / "hosts").string(), "--force"});
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_NE(forced.output.find("6 frame(s) rendered, 0 skipped"), std::string::npos)
      << forced.output;
  EXPECT_NE(fs::last_write_time(scene / frame_name(1)), before);
}

// The local render skips frames with an image as the farm does (an empty image is no image),
// renders the others in ranges that do not cross the skipped frames, and --force renders all.
TEST_F(FarmScene, LocalRenderSkipsFramesWithAnImageUnlessForced) {
  const fs::path scene = copy_scene("local_resume");
  for (int f : {1, 2, 3, 5}) fs::copy_file(reference() / frame_name(f), scene / frame_name(f));
  write_text(scene / frame_name(6), "");
  const auto before = fs::last_write_time(scene / frame_name(1));
  write_logging_povray(work_ / "bin", work_ / "runs.log");
  const ScopedEnvironmentVariable path_variable = path_with_first(work_ / "bin");
  const CommandResult r = run_toonwater({"render", scene.string(), "--jobs", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("2 frame(s) rendered, 4 skipped (already rendered), 0 failed"),
            std::string::npos)
      << r.output;
  const std::string runs = read_text(work_ / "runs.log");
  EXPECT_EQ(std::count(runs.begin(), runs.end(), '\n'), 2) << runs;
  for (const char* range : {"+SF4 +EF4", "+SF6 +EF6"})
    EXPECT_NE(runs.find(range), std::string::npos) << range << " in " << runs;
  EXPECT_EQ(fs::last_write_time(scene / frame_name(1)), before);
  expect_frames_like(scene, reference());

  const CommandResult forced = run_toonwater({"render", scene.string(), "--jobs", "2", "--force"});
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  EXPECT_NE(forced.output.find("6 frame(s) rendered, 0 skipped"), std::string::npos)
      << forced.output;
  EXPECT_NE(fs::last_write_time(scene / frame_name(1)), before);
  expect_frames_like(scene, reference());
}

// povgen carries an earlier scene's images over when it rewrites the directory: they are older
// than the new scene, so the render draws every frame again instead of keeping stale pictures.
TEST_F(FarmScene, ImagesOfAnEarlierSceneAreRenderedAgain) {
  const fs::path scene = work_ / "rewritten";
  fs::copy(reference(), scene, fs::copy_options::recursive);
  const int wider = kFarmWidth + 16;
  const CommandResult pov =
      run_toonwater({"povgen", "--config", (dir_->path() / "scene.toml").string(), "--water",
                     (dir_->path() / "sim/water_####.obj").string(), "--set",
                     "render.width=" + std::to_string(wider), "--set",
                     "render.height=" + std::to_string(kFarmHeight), "--out", scene.string()});
  ASSERT_EQ(pov.exit_code, 0) << pov.output;
  ASSERT_TRUE(fs::exists(scene / frame_name(1)));  // carried over from the earlier scene

  const CommandResult r = run_toonwater({"render", scene.string(), "--jobs", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(kFarmFrames) + " frame(s) rendered, 0 skipped"),
            std::string::npos)
      << r.output;
  for (int f = 1; f <= kFarmFrames; ++f)
    EXPECT_EQ(read_image(scene / frame_name(f)).width, wider) << f;

  // Rendered now, the images are the scene's: a second render skips them all.
  const CommandResult again = run_toonwater({"render", scene.string(), "--jobs", "2"});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 frame(s) rendered, " + std::to_string(kFarmFrames) + " skipped"),
            std::string::npos)
      << again.output;
}

TEST_F(FarmScene, MissingOrFailingSbatchIsAClearErrorWithTheCommand) {
  const fs::path scene = copy_scene("nosbatch");
  fs::create_directories(work_ / "empty");
  const ScopedEnvironmentVariable path_variable("PATH", (work_ / "empty").string());
  const CommandResult missing = run_toonwater({"render", scene.string(), "--on", "slurm"});
  EXPECT_NE(missing.exit_code, 0);
  EXPECT_NE(missing.output.find("cannot run 'sbatch --parsable"), std::string::npos)
      << missing.output;
  EXPECT_NE(missing.output.find("sbatch not found"), std::string::npos) << missing.output;

  // A Slurm whose controller is down: sbatch's own message, and the command line.
  write_text(work_ / "empty/sbatch",
             "#!/bin/sh\necho 'sbatch: error: Batch job submission failed: Unable to contact slurm "
             "controller (connect failure)' >&2\nexit 1\n");
  fs::permissions(work_ / "empty/sbatch", fs::perms::owner_all);
  const CommandResult failing =
      run_toonwater({"render", scene.string(), "--on", "slurm", "--partition", "gpu"});
  EXPECT_NE(failing.exit_code, 0);
  EXPECT_NE(failing.output.find("Unable to contact slurm controller"), std::string::npos)
      << failing.output;
  EXPECT_NE(failing.output.find("'sbatch --parsable"), std::string::npos) << failing.output;
  EXPECT_NE(failing.output.find("--partition=gpu"), std::string::npos) << failing.output;
  for (int f = 1; f <= kFarmFrames; ++f) EXPECT_FALSE(fs::exists(scene / frame_name(f)));
}

}  // namespace
}  // namespace toonwater::test
