// Nothing lost: `toonwater povgen` and `toonwater render` interrupted by SIGINT, SIGTERM or SIGHUP
// in the middle of a sequence stop with the "interrupted" exit code and leave no temporary or
// partial file and no povray process behind. povgen leaves the scene directory exactly as it was
// (none in a fresh place, the earlier complete scene otherwise); render keeps the images it
// finished. Running the command again completes the sequence.
//
// No timing is asserted: the signal is sent once the progress display shows a few frames done, and
// the sequences are long enough that the run is still going then. Waits are generous.
#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

// A toonwater process running in the background, its output in a log file.
class Background {
 public:
  // toonwater with `args`, and with `environment` added to the test's own.
  Background(const std::vector<std::string>& args, fs::path log,
             const std::map<std::string, std::string>& environment = {})
      : log_(std::move(log)) {
    pid_ = ::fork();
    if (pid_ == 0) {
      const int fd = ::open(log_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      if (fd < 0) ::_exit(126);
      ::dup2(fd, STDOUT_FILENO);
      ::dup2(fd, STDERR_FILENO);
      for (const auto& [name, value] : environment) ::setenv(name.c_str(), value.c_str(), 1);
      std::string exe = TOONWATER_EXECUTABLE;
      std::vector<std::string> copies = args;
      std::vector<char*> argv{exe.data()};
      for (auto& a : copies) argv.push_back(a.data());
      argv.push_back(nullptr);
      ::execv(exe.c_str(), argv.data());
      ::_exit(127);
    }
  }
  ~Background() {
    if (pid_ > 0 && !exited_) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
  }

  // Waits until the output contains `text`; false if the process ended first or time ran out.
  bool wait_for_output(const std::string& text, std::chrono::seconds limit = 600s) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < deadline) {
      if (output().find(text) != std::string::npos) return true;
      int status = 0;
      if (::waitpid(pid_, &status, WNOHANG) == pid_) {
        exited_ = true;
        status_ = status;
        return false;
      }
      std::this_thread::sleep_for(5ms);
    }
    return false;
  }

  void signal(int number) { ::kill(pid_, number); }

  // Waits for the end; the exit code, 128 + signal when killed, -1 when it had to be killed.
  int wait(std::chrono::seconds limit = 600s) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!exited_) {
      if (::waitpid(pid_, &status_, WNOHANG) == pid_) {
        exited_ = true;
        break;
      }
      if (std::chrono::steady_clock::now() > deadline) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, nullptr, 0);
        exited_ = true;
        return -1;
      }
      std::this_thread::sleep_for(10ms);
    }
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : 128 + WTERMSIG(status_);
  }

  std::string output() const { return fs::exists(log_) ? read_text(log_) : ""; }

 private:
  fs::path log_;
  pid_t pid_ = -1;
  bool exited_ = false;
  int status_ = 0;
};

// Names in `dir` that a finished run must not leave: temporaries of atomic writes (".NAME.tmp-")
// and render's per-frame directories (".render-N.tmp-") and logs.
std::vector<std::string> leftovers(const fs::path& dir) {
  std::vector<std::string> found;
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name.find(".tmp") != std::string::npos || name.starts_with("render_") ||
        (name[0] == '.' && name != ".toonwater-scene"))
      found.push_back(name);
  }
  return found;
}

// Every file of `dir` by name, with its content.
std::map<std::string, std::string> contents(const fs::path& dir) {
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::directory_iterator(dir))
    if (entry.is_regular_file()) files[entry.path().filename().string()] = read_text(entry.path());
  return files;
}

// True when some process runs with `dir` as its working directory (a povray left running).
bool process_runs_in(const fs::path& dir) {
  const fs::path target = fs::canonical(dir);
  for (const auto& entry : fs::directory_iterator("/proc")) {
    std::error_code ec;
    const fs::path cwd = fs::read_symlink(entry.path() / "cwd", ec);
    if (!ec && cwd == target) return true;
  }
  return false;
}

constexpr int frame_count = 30;

// frame_count water frames (hard links to one grid x grid mesh) in `dir`.
fs::path make_sequence(const fs::path& dir, int grid) {
  write_obj(dir / "water_0000.obj", make_height_grid(grid, 1.0, [](double x, double z) {
              return 0.1 * std::sin(4 * x) * std::cos(3 * z);
            }));
  for (int f = 1; f < frame_count; ++f) {
    char name[32];
    std::snprintf(name, sizeof name, "water_%04d.obj", f);
    fs::create_hard_link(dir / "water_0000.obj", dir / name);
  }
  return dir / "water_####.obj";
}

class Interrupt : public ::testing::TestWithParam<int> {};

TEST_P(Interrupt, PovgenKeepsFinishedFramesAndLeavesNothingPartial) {
  ScratchDir dir;
  const fs::path pattern = make_sequence(dir.path(), 120);
  const fs::path out = dir / "scene";
  const std::vector<std::string> args{"povgen", "--water", pattern.string(), "--out", out.string()};

  // Interrupted in a fresh place: no scene directory at all, nothing left beside it.
  {
    Background run(args, dir / "first.log");
    ASSERT_TRUE(run.wait_for_output("frame 3/")) << run.output();
    run.signal(GetParam());
    const int code = run.wait();
    EXPECT_EQ(code, 4) << run.output();
    EXPECT_NE(run.output().find("interrupted"), std::string::npos) << run.output();
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{});

  // Run again: every frame is done and the directory is complete.
  const CommandResult full = run_toonwater(args);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  const auto good = contents(out);
  ASSERT_EQ(good.size(), frame_count + 4u)
      << "water includes, toon.inc, scene.ini, scene.pov, .toonwater-scene";
  for (const auto& [name, text] : good) {
    if (name.starts_with("water_")) {
      EXPECT_EQ(text, good.at("water_0000.inc")) << name;
    }
  }

  // Interrupted over that complete directory: everything from the good run is still there, whole.
  {
    Background run(args, dir / "third.log");
    ASSERT_TRUE(run.wait_for_output("frame 3/")) << run.output();
    run.signal(GetParam());
    EXPECT_EQ(run.wait(), 4) << run.output();
  }
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
  EXPECT_EQ(leftovers(dir.path()), std::vector<std::string>{});
  EXPECT_EQ(contents(out), good);
}

TEST_P(Interrupt, RenderStopsPovrayAndLeavesOnlyWholeImages) {
  ScratchDir dir;
  const fs::path pattern = make_sequence(dir.path(), 12);
  const fs::path out = dir / "scene";
  const CommandResult made =
      run_toonwater({"povgen", "--water", pattern.string(), "--out", out.string(), "--set",
                     "render.width=48", "--set", "render.height=36"});
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const std::vector<std::string> args{"render", out.string(), "--jobs", "2"};
  const auto images = [&] {
    std::vector<fs::path> found;
    for (const auto& entry : fs::directory_iterator(out))
      if (entry.path().extension() == ".png") found.push_back(entry.path());
    return found;
  };
  const auto expect_whole_images = [&] {
    for (const fs::path& png : images()) {
      const Image image = read_image(png);  // throws on a truncated or broken file
      EXPECT_EQ(image.width, 48) << png;
      EXPECT_EQ(image.height, 36) << png;
    }
  };

  {
    Background run(args, dir / "first.log");
    ASSERT_TRUE(run.wait_for_output("frame 4/")) << run.output();
    run.signal(GetParam());
    EXPECT_NE(run.wait(), 0) << run.output();
    EXPECT_NE(run.output().find("interrupted"), std::string::npos) << run.output();
  }
  EXPECT_FALSE(process_runs_in(out)) << "a povray process outlived toonwater render";
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
  EXPECT_GE(images().size(), 4u);
  EXPECT_LT(images().size(), static_cast<std::size_t>(frame_count));
  expect_whole_images();

  // Run again: every frame renders.
  const CommandResult full = run_toonwater(args);
  ASSERT_EQ(full.exit_code, 0) << full.output;
  EXPECT_EQ(images().size(), static_cast<std::size_t>(frame_count));
  expect_whole_images();

  // Interrupted over the complete set (--force: every frame has its image): all images stay whole.
  {
    std::vector<std::string> forced = args;
    forced.push_back("--force");
    Background run(forced, dir / "third.log");
    ASSERT_TRUE(run.wait_for_output("frame 4/")) << run.output();
    run.signal(GetParam());
    EXPECT_NE(run.wait(), 0) << run.output();
  }
  EXPECT_FALSE(process_runs_in(out));
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
  EXPECT_EQ(images().size(), static_cast<std::size_t>(frame_count));
  expect_whole_images();
}

INSTANTIATE_TEST_SUITE_P(Signals, Interrupt, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& signal) {
                           return signal.param == SIGINT    ? "SIGINT"
                                  : signal.param == SIGTERM ? "SIGTERM"
                                                            : "SIGHUP";
                         });

// A scene of frame_count small frames in `dir`/scene, for render.
fs::path small_scene(const fs::path& dir) {
  const fs::path pattern = make_sequence(dir, 12);
  const fs::path out = dir / "scene";
  const CommandResult made =
      run_toonwater({"povgen", "--water", pattern.string(), "--out", out.string(), "--set",
                     "render.width=48", "--set", "render.height=36"});
  EXPECT_EQ(made.exit_code, 0) << made.output;
  return out;
}

bool eventually_no_process_in(const fs::path& dir) {
  for (int i = 0; i < 200; ++i) {
    if (!process_runs_in(dir)) return true;
    std::this_thread::sleep_for(50ms);
  }
  return false;
}

TEST(InterruptOutright, ARenderKilledBySigkillLeavesNoPovrayRunningAndTheNextRunCleansUp) {
  ScratchDir dir;
  const fs::path out = small_scene(dir.path());
  // A POV-Ray that would run for a minute, telling its process id.
  const fs::path povray = dir / "slow-povray", pid_file = dir / "povray.pid";
  write_text(povray, "#!/bin/sh\necho $$ > '" + pid_file.string() + "'\nexec sleep 60\n");
  fs::permissions(povray, fs::perms::owner_all);
  {
    Background run({"render", out.string(), "--jobs", "1"}, dir / "killed.log",
                   {{"TOONWATER_POVRAY", povray.string()}});
    for (int i = 0; i < 1000 && !(fs::exists(pid_file) && fs::file_size(pid_file) > 1); ++i)
      std::this_thread::sleep_for(10ms);
    ASSERT_TRUE(fs::exists(pid_file)) << run.output();
    run.signal(SIGKILL);
    EXPECT_EQ(run.wait(), 128 + SIGKILL);
  }
  const pid_t povray_pid = std::stoi(read_text(pid_file));
  // Gone, or a zombie waiting for whichever process adopted it to reap it.
  auto ended = [&] {
    if (::kill(povray_pid, 0) != 0) return true;
    const std::string stat = read_text("/proc/" + std::to_string(povray_pid) + "/stat");
    const std::size_t close = stat.rfind(')');
    return close != std::string::npos && close + 2 < stat.size() && stat[close + 2] == 'Z';
  };
  bool gone = false;
  for (int i = 0; i < 200 && !gone; ++i) {
    gone = ended();
    if (!gone) std::this_thread::sleep_for(50ms);
  }
  EXPECT_TRUE(gone) << "POV-Ray (pid " << povray_pid << ") outlived a render killed outright";
  const CommandResult again = run_toonwater({"render", out.string()});
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_EQ(leftovers(out), std::vector<std::string>{}) << "the killed run's temporaries";
}

TEST(InterruptOutright, ARenderOnGnuParallelStopsItsTasksOnSigterm) {
  if (::system("parallel --version > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "GNU parallel is not installed";
  ScratchDir dir;
  const fs::path out = small_scene(dir.path());
  // POV-Ray on PATH that runs for a minute, each telling its process id.
  const fs::path bin = dir / "bin", pids = dir / "pids";
  fs::create_directories(bin);
  fs::create_directories(pids);
  write_text(bin / "povray", "#!/bin/sh\necho $$ > '" + pids.string() + "/'$$\nexec sleep 60\n");
  fs::permissions(bin / "povray", fs::perms::owner_all);
  write_text(dir / "hosts", ":\n");
  int code = 0;
  std::string output;
  {
    Background run({"render", out.string(), "--on", "parallel", "--hosts", (dir / "hosts").string(),
                    "--frames-per-task", "5"},
                   dir / "farm.log", {{"PATH", path_value_with_first(bin)}});
    for (int i = 0; i < 3000 && fs::is_empty(pids); ++i) std::this_thread::sleep_for(10ms);
    ASSERT_FALSE(fs::is_empty(pids)) << run.output();
    run.signal(SIGTERM);
    code = run.wait(120s);
    output = run.output();
  }
  EXPECT_EQ(code, 4) << output;
  EXPECT_NE(output.find("interrupted"), std::string::npos) << output;
  for (const auto& entry : fs::directory_iterator(pids)) {
    const pid_t pid = std::stoi(entry.path().filename().string());
    bool gone = false;
    for (int i = 0; i < 200 && !gone; ++i) {
      gone = ::kill(pid, 0) != 0 ||
             read_text("/proc/" + std::to_string(pid) + "/stat").find(") Z") != std::string::npos;
      if (!gone) std::this_thread::sleep_for(50ms);
    }
    EXPECT_TRUE(gone) << "a task's POV-Ray (pid " << pid << ") outlived the stopped farm";
  }
}

TEST(InterruptOutright, ARenderWhoseStandardErrorIsAClosedPipeFinishesItsWork) {
  ScratchDir dir;
  const fs::path out = small_scene(dir.path());
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);  // nobody reads: every write to stderr raises SIGPIPE
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::dup2(fds[1], STDERR_FILENO);
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    std::string exe = TOONWATER_EXECUTABLE, render = "render", scene = out.string();
    char* argv[] = {exe.data(), render.data(), scene.data(), nullptr};
    ::execv(exe.c_str(), argv);
    ::_exit(127);
  }
  ::close(fds[1]);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status);
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_TRUE(eventually_no_process_in(out));
  std::size_t pngs = 0;
  for (const auto& entry : fs::directory_iterator(out)) pngs += entry.path().extension() == ".png";
  EXPECT_EQ(pngs, static_cast<std::size_t>(frame_count));
  EXPECT_EQ(leftovers(out), std::vector<std::string>{});
}

}  // namespace
}  // namespace toonwater::test
