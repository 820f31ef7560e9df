// remove_temporaries_on_signals (common/atomic_file.hpp): a process ended by SIGINT, SIGTERM
// or SIGHUP while AtomicFileWriters are writing leaves their targets as they were and no
// temporary file. Each case runs in a child process that signals itself mid-write.
#include "common/atomic_file.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <signal.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <memory>
#include <thread>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class AtomicFileSignals : public ::testing::TestWithParam<int> {};

TEST_P(AtomicFileSignals, InterruptedWritesLeaveTheTargetsAndNoTemporary) {
  ScratchDir dir;
  write_text(dir / "a.csv", "good a\n");
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    remove_temporaries_on_signals();
    write_file_atomically(dir / "done.csv", "complete\n");  // finished before the signal
    AtomicFileWriter a(dir / "a.csv");
    AtomicFileWriter b(dir / "b.ply");
    a.write("partial");
    b.write("partial");
    ::raise(GetParam());
    ::_exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status)) << "the signal ends the process as it would have";
  EXPECT_EQ(WTERMSIG(status), GetParam());
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"a.csv", "done.csv"}));
  EXPECT_EQ(read_text(dir / "a.csv"), "good a\n");
  EXPECT_EQ(read_text(dir / "done.csv"), "complete\n");
}

// A signal that comes while a batch's renames run waits for the last of them: the outputs are
// all new, never some new and some old. The signal is sent, from a second thread, once the
// first target has been replaced, so it lands among the renames.
TEST_P(AtomicFileSignals, ASignalDuringABatchsRenamesWaitsForTheLast) {
  ScratchDir dir;
  constexpr int files = 60;  // within the table of writers a signal can clean up after
  const std::string old_text(1 << 16, 'o'), new_text(1 << 16, 'n');
  for (int i = 0; i < files; ++i) write_text(dir / ("out" + std::to_string(i)), old_text);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    remove_temporaries_on_signals();
    std::thread signaller([&] {
      while (read_text(dir / "out0") != new_text) {
      }
      ::kill(::getpid(), GetParam());
    });
    signaller.detach();
    {
      OutputBatch batch;
      std::vector<std::unique_ptr<AtomicFileWriter>> writers;
      for (int i = 0; i < files; ++i) {
        writers.push_back(std::make_unique<AtomicFileWriter>(dir / ("out" + std::to_string(i))));
        writers.back()->write(new_text);
        writers.back()->commit();
      }
      batch.commit();
    }
    for (;;) ::pause();  // the signal ends the process, during the commit or after it
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(WIFSIGNALED(status));
  EXPECT_EQ(WTERMSIG(status), GetParam());
  int replaced = 0;
  for (int i = 0; i < files; ++i)
    replaced += read_text(dir / ("out" + std::to_string(i))) == new_text;
  EXPECT_EQ(replaced, files) << "the first target was replaced, so every one must be";
  EXPECT_EQ(names_in(dir.path()).size(), static_cast<std::size_t>(files)) << "no temporary left";
}

INSTANTIATE_TEST_SUITE_P(Signals, AtomicFileSignals, ::testing::Values(SIGINT, SIGTERM, SIGHUP),
                         [](const ::testing::TestParamInfo<int>& signal) {
                           return std::string(sigabbrev_np(signal.param));
                         });

}  // namespace
}  // namespace toonwater::test
