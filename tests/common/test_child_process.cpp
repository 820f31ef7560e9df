// Child processes (common/child_process.hpp): where their output goes, where they run, what
// their standard input is, and the exit statuses of a child that cannot become its program.
#include "common/child_process.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

int wait_exit_status(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return exit_status(status);
}

class ChildProcess : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("toonwater_child_process_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ChildProcess, OutputAndErrorGoIntoTheFileInTheWorkingDirectoryAndInputIsEmpty) {
  const fs::path log = dir_ / "log.txt";
  { std::ofstream(log) << "an earlier run's text, longer than the new one\n"; }
  fs::create_directories(dir_ / "work");
  ChildSetup setup;
  setup.working_directory = (dir_ / "work").string();
  setup.output_file = log.string();
  // pwd names the working directory; cat shows standard input is empty (not the terminal's).
  const pid_t pid =
      start_child_process({"sh", "-c", "pwd; echo to-error >&2; cat; echo end; exit 3"}, setup);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit_status(pid), 3);
  EXPECT_EQ(test::read_text(log), fs::canonical(dir_ / "work").string() + "\nto-error\nend\n");
}

TEST_F(ChildProcess, OutputAndErrorGoIntoTheDescriptorsGiven) {
  int out[2], err[2];
  ASSERT_EQ(::pipe2(out, O_CLOEXEC), 0);
  ASSERT_EQ(::pipe2(err, O_CLOEXEC), 0);
  ChildSetup setup;
  setup.out_fd = out[1];
  setup.err_fd = err[1];
  const pid_t pid = start_child_process({"sh", "-c", "echo out; echo err >&2"}, setup);
  ::close(out[1]);
  ::close(err[1]);
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit_status(pid), 0);
  char buffer[64] = {};
  EXPECT_EQ(::read(out[0], buffer, sizeof buffer), 4);
  EXPECT_EQ(std::string(buffer, 4), "out\n");
  EXPECT_EQ(::read(err[0], buffer, sizeof buffer), 4);
  EXPECT_EQ(std::string(buffer, 4), "err\n");
  ::close(out[0]);
  ::close(err[0]);
}

TEST_F(ChildProcess, AChildThatCannotBecomeItsProgramSaysWhy) {
  ChildSetup no_log;
  no_log.output_file = (dir_ / "missing" / "log.txt").string();
  EXPECT_EQ(wait_exit_status(start_child_process({"true"}, no_log)), child_cannot_write_output);

  ChildSetup no_directory;
  no_directory.working_directory = (dir_ / "missing").string();
  EXPECT_EQ(wait_exit_status(start_child_process({"true"}, no_directory)),
            child_cannot_enter_directory);

  EXPECT_EQ(wait_exit_status(start_child_process({"toonwater-no-such-program"}, ChildSetup{})),
            child_cannot_execute);
}

TEST_F(ChildProcess, ASignalEndingTheChildIs128PlusItsNumber) {
  const pid_t pid = start_child_process({"sh", "-c", "kill -9 $$"}, ChildSetup{});
  ASSERT_GT(pid, 0);
  EXPECT_EQ(wait_exit_status(pid), 128 + 9);
}

// toonwater stops on SIGTERM with a handler that only sets a flag, which a child inherits until
// it becomes its program. A child stopped in that window (a render stopped just as it starts
// POV-Ray) must still end: with the handler, the signal would be taken and lost, and the program
// would run on. Each child here is stopped at once, most of them before their exec.
volatile std::sig_atomic_t parent_stops = 0;
void note_stop(int) { parent_stops = parent_stops + 1; }

TEST_F(ChildProcess, AChildStoppedBeforeItBecomesItsProgramEndsAndTheParentKeepsItsHandler) {
  struct sigaction handler {
  }, previous{};
  handler.sa_handler = note_stop;
  ASSERT_EQ(::sigaction(SIGTERM, &handler, &previous), 0);
  for (int round = 0; round < 30; ++round) {
    const pid_t pid = start_child_process({"sleep", "5"}, ChildSetup{});
    ASSERT_GT(pid, 0);
    ::kill(pid, SIGTERM);
    const auto start = std::chrono::steady_clock::now();
    EXPECT_EQ(wait_exit_status(pid), 128 + SIGTERM) << "round " << round;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(4)) << round;
  }
  ::raise(SIGTERM);  // the parent's own handler is still in place
  EXPECT_EQ(parent_stops, 1);
  ::sigaction(SIGTERM, &previous, nullptr);
}

}  // namespace
}  // namespace toonwater
