// parallel_chunks: every index once, nested and concurrent calls, calls at any pace, a throwing
// chunk, a forked child.
#include "common/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <sys/wait.h>
#include <unistd.h>

namespace toonwater {
namespace {

// How many times each index of [0, n) was visited by one call over `workers` chunks.
std::vector<int> visits(std::size_t n, std::size_t workers) {
  std::vector<std::atomic<int>> count(n);
  parallel_chunks(n, workers, [&](std::size_t, std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) count[i].fetch_add(1);
  });
  std::vector<int> result;
  for (const auto& c : count) result.push_back(c.load());
  return result;
}

TEST(ParallelChunks, VisitsEveryIndexOnceForAnyChunkCount) {
  for (std::size_t workers : {1u, 2u, 3u, 8u})
    for (std::size_t n : {0u, 1u, 7u, 1000u})
      for (int repeat = 0; repeat < 20; ++repeat)
        EXPECT_EQ(visits(n, workers), std::vector<int>(n, 1)) << n << " over " << workers;
}

TEST(ParallelChunks, ChunksCoverTheirRangeInOrder) {
  std::vector<std::pair<std::size_t, std::size_t>> ranges(4);
  parallel_chunks(10, 4, [&](std::size_t chunk, std::size_t begin, std::size_t end) { ranges[chunk] = {begin, end}; });
  std::size_t next = 0;
  for (const auto& [begin, end] : ranges) {
    EXPECT_EQ(begin, next);
    EXPECT_LE(begin, end);
    next = end;
  }
  EXPECT_EQ(next, 10u);
}

TEST(ParallelChunks, NestedAndConcurrentCallsComplete) {
  std::atomic<int> inner{0};
  parallel_chunks(2, 2, [&](std::size_t, std::size_t, std::size_t) {
    parallel_chunks(100, 2, [&](std::size_t, std::size_t begin, std::size_t end) { inner += int(end - begin); });
  });
  EXPECT_EQ(inner.load(), 200);

  std::atomic<int> total{0};
  std::thread other([&] {
    for (int i = 0; i < 50; ++i) total += visits(64, 2)[3];
  });
  for (int i = 0; i < 50; ++i) total += visits(64, 2)[5];
  other.join();
  EXPECT_EQ(total.load(), 100);
}

// The calling thread's chunk throws while another chunk still reads the caller's data: the call
// waits for it before the exception leaves, and the pool serves the next call.
TEST(ParallelChunks, ExceptionOfTheCallersChunkWaitsForTheOthers) {
  std::atomic<bool> other_finished{false};
  EXPECT_THROW(parallel_chunks(2, 2,
                               [&](std::size_t chunk, std::size_t, std::size_t) {
                                 if (chunk == 0) throw std::runtime_error("chunk 0");
                                 std::this_thread::sleep_for(std::chrono::milliseconds(50));
                                 other_finished = true;
                               }),
               std::runtime_error);
  if (std::thread::hardware_concurrency() > 1) {
    EXPECT_TRUE(other_finished.load());
  }
  EXPECT_EQ(visits(100, 2), std::vector<int>(100, 1));
}

// The pool's thread and the caller watch for each other briefly before they sleep, and stop
// watching after a wait that outlasted the watch: calls that come at once, after pauses longer
// than the watch, or whose other chunk ends long after the caller's, all run every chunk and
// return only once it has finished.
TEST(ParallelChunks, CallsAtAnyPaceWaitForEveryChunk) {
  using std::chrono::microseconds;
  const microseconds pauses[] = {microseconds(0), microseconds(20), microseconds(300),
                                 microseconds(2000)};
  for (int round = 0; round < 3; ++round)
    for (const microseconds pause : pauses)
      for (const microseconds slower : {microseconds(0), microseconds(300)}) {
        std::this_thread::sleep_for(pause);
        std::atomic<int> finished{0};
        parallel_chunks(2, 2, [&](std::size_t chunk, std::size_t, std::size_t) {
          if (chunk == 1) std::this_thread::sleep_for(slower);
          finished.fetch_add(1);
        });
        EXPECT_EQ(finished.load(), 2) << "pause " << pause.count() << " µs, other chunk "
                                      << slower.count() << " µs slower";
      }
  EXPECT_EQ(visits(1000, 2), std::vector<int>(1000, 1));
}

TEST(ParallelChunks, WorksInAForkedChild) {
  EXPECT_EQ(visits(100, 2), std::vector<int>(100, 1));  // the pool runs in this process
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    _exit(visits(100, 2) == std::vector<int>(100, 1) ? 0 : 1);
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
}

}  // namespace
}  // namespace toonwater
