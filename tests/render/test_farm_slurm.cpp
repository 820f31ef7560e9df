// Render farms on a real Slurm: the single-node cluster of scripts/slurm-local.sh (started by
// the ctest fixture slurm_cluster; TOONWATER_SLURM_DIR names its directory). Job arrays from the
// demo's wake scene, compared pixel for pixel with the local `toonwater render`. Skips, with the
// reason, where this machine cannot run Slurm.
#include "tests/render/farm_test_util.hpp"

#include "render/farm.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

class SlurmFarm : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const char* cluster = std::getenv("TOONWATER_SLURM_DIR");
    if (!cluster) {
      skip_reason_ = "TOONWATER_SLURM_DIR is not set (run through ctest: its fixture starts Slurm)";
      return;
    }
    const fs::path dir(cluster);
    if (fs::exists(dir / "unavailable")) {
      skip_reason_ = "Slurm cannot run on this machine: " + read_text(dir / "unavailable");
      return;
    }
    if (!fs::exists(dir / "env")) {
      skip_reason_ = "the Slurm cluster in " + dir.string() + " was not started";
      return;
    }
    ::setenv("SLURM_CONF", (dir / "slurm.conf").c_str(), 1);
    dir_ = new ScratchDir;
    scene_ = make_wake_scene(*dir_);
  }
  static void TearDownTestSuite() { delete dir_; }
  // The local render, made when a test first compares with it.
  static const fs::path& reference() {
    if (reference_.empty()) reference_ = render_locally(*dir_, scene_);
    return reference_;
  }
  void SetUp() override {
    if (!skip_reason_.empty()) GTEST_SKIP() << skip_reason_;
  }
  fs::path copy_scene(const std::string& name) const {
    const fs::path copy = work_ / name;
    fs::copy(scene_, copy, fs::copy_options::recursive);
    return copy;
  }
  static std::string skip_reason_;
  static ScratchDir* dir_;
  static fs::path scene_, reference_;
  ScratchDir work_;
};
std::string SlurmFarm::skip_reason_;
ScratchDir* SlurmFarm::dir_ = nullptr;
fs::path SlurmFarm::scene_, SlurmFarm::reference_;

TEST_F(SlurmFarm, JobArrayRendersEveryFrameLikeTheLocalRender) {
  const fs::path scene = copy_scene("array");
  const CommandResult r = run_toonwater({"render", scene.string(), "--on", "slurm", "--partition",
                                         "local", "--frames-per-task", "2"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("3 task(s) over 6 frame(s) submitted"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("6/6 frames, 0 task(s) running, 0 pending"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("6 frame(s) rendered, 0 skipped"), std::string::npos) << r.output;
  expect_frames_like(scene, reference());
  // A log per task, written by the task on the node.
  std::size_t logs = 0;
  for (const auto& entry : fs::directory_iterator(scene / ".farm"))
    if (entry.path().filename().string().rfind("slurm-", 0) == 0 &&
        entry.path().extension() == ".log") {
      EXPECT_NE(read_text(entry.path()).find("render-task: frames"), std::string::npos);
      ++logs;
    }
  EXPECT_EQ(logs, 3u);
}

TEST_F(SlurmFarm, NoWaitPrintsTheJobIdAndStatusReportsProgressToTheEnd) {
  const fs::path scene = copy_scene("nowait");
  const CommandResult r = run_toonwater(
      {"render", scene.string(), "--on", "slurm", "--frames-per-task", "3", "--no-wait"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string id = r.output.substr(r.output.rfind('\n', r.output.size() - 2) + 1);
  ASSERT_FALSE(id.empty());
  const long job = std::stol(id);  // the last line is the job id alone
  EXPECT_GT(job, 0);
  std::string status;
  for (int i = 0; i < 600; ++i) {
    const CommandResult s = run_toonwater({"render", scene.string(), "--status"});
    ASSERT_EQ(s.exit_code, 0) << s.output;
    status = s.output;
    ASSERT_NE(status.find("slurm job " + std::to_string(job)), std::string::npos) << status;
    if (status.find("finished") != std::string::npos) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
  }
  EXPECT_NE(status.find("finished: 6/6 frames"), std::string::npos) << status;
  expect_frames_like(scene, reference());
}

TEST_F(SlurmFarm, SigtermCancelsTheJobAndExitsInterrupted) {
  const fs::path scene = copy_scene("stopped");
  // POV-Ray on PATH that runs for a minute (sbatch passes the environment to the tasks).
  const fs::path bin = work_ / "bin", started = work_ / "started";
  fs::create_directories(bin);
  write_text(bin / "povray", "#!/bin/sh\ntouch '" + started.string() + "'\nexec sleep 60\n");
  fs::permissions(bin / "povray", fs::perms::owner_all);
  const std::string path = path_value_with_first(bin);
  const fs::path log = work_ / "render.log";
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setenv("PATH", path.c_str(), 1);
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, STDERR_FILENO);
    ::dup2(fd, STDOUT_FILENO);
    std::string exe = TOONWATER_EXECUTABLE, render = "render", dir = scene.string(), on = "--on",
                slurm = "slurm";
    char* argv[] = {exe.data(), render.data(), dir.data(), on.data(), slurm.data(), nullptr};
    ::execv(exe.c_str(), argv);
    ::_exit(127);
  }
  for (int i = 0; i < 6000 && !fs::exists(started); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(fs::exists(started)) << read_text(log);
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  const std::string output = read_text(log);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status) << "\n" << output;
  EXPECT_EQ(WEXITSTATUS(status), 4) << output;
  EXPECT_NE(output.find("cancelled"), std::string::npos) << output;
  const std::size_t at = output.find("slurm job ");
  ASSERT_NE(at, std::string::npos) << output;
  const std::string job = output.substr(at + 10, output.find(':', at) - at - 10);
  bool gone = false;
  for (int i = 0; i < 300 && !gone; ++i) {
    gone =
        run_command({"squeue", "-h", "-j", job}).out.find_first_not_of(" \n") == std::string::npos;
    if (!gone) std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  EXPECT_TRUE(gone) << "slurm job " << job << " still queued or running";
}

TEST_F(SlurmFarm, ATaskKilledMidFrameLeavesNoPartialImageAndIsResubmitted) {
  const fs::path scene = copy_scene("killed");
  reference();  // rendered before the faulty povray is on PATH
  write_killing_povray(work_ / "bin", work_ / "killed-once");
  // sbatch passes the environment to the tasks.
  const ScopedEnvironmentVariable path_variable = path_with_first(work_ / "bin");
  const CommandResult r =
      run_toonwater({"render", scene.string(), "--on", "slurm", "--frames-per-task", "3"});
  ASSERT_TRUE(fs::exists(work_ / "killed-once"));  // the fault happened
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The killed task's frames without a whole image (how many it finished in its 0.5 s varies;
  // a whole PNG is kept) are resubmitted.
  EXPECT_NE(r.output.find("frame(s) missing after the tasks ended; resubmitted"), std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("1 task(s) resubmitted"), std::string::npos) << r.output;
  expect_frames_like(scene, reference());
}

TEST_F(SlurmFarm, AFrameThatFailsTwiceIsReportedWithPovRaysMessage) {
  const fs::path scene = copy_scene("broken");
  fs::remove(scene / "water_0005.inc");
  const CommandResult r =
      run_toonwater({"render", scene.string(), "--on", "slurm", "--frames-per-task", "3"});
  EXPECT_EQ(r.exit_code, 5) << r.output;  // POV-Ray failed
  EXPECT_NE(r.output.find("render: frame 5 failed:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("water_0005.inc"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("5 frame(s) rendered, 0 skipped (already rendered), 1 failed"),
            std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(scene / frame_name(5)));
  for (int f : {1, 2, 3, 4, 6})
    EXPECT_EQ(read_image(scene / frame_name(f)).pixels,
              read_image(reference() / frame_name(f)).pixels)
        << f;
}

TEST_F(SlurmFarm, ResumedRunSkipsFramesWithAnImage) {
  const fs::path scene = copy_scene("resume");
  for (int f : {1, 2, 6}) fs::copy_file(reference() / frame_name(f), scene / frame_name(f));
  const auto before = fs::last_write_time(scene / frame_name(2));
  const CommandResult r = run_toonwater({"render", scene.string(), "--on", "slurm"});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("1 task(s) over 3 frame(s) submitted"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("3 frame(s) rendered, 3 skipped"), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(scene / frame_name(2)), before);
  expect_frames_like(scene, reference());
}

TEST_F(SlurmFarm, AWrongPartitionIsSlurmsOwnMessage) {
  const fs::path scene = copy_scene("partition");
  const CommandResult r =
      run_toonwater({"render", scene.string(), "--on", "slurm", "--partition", "nosuchpartition"});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("sbatch: error: invalid partition specified: nosuchpartition"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("--partition=nosuchpartition"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace toonwater::test
