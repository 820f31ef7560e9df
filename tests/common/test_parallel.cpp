// parallel.hpp: every index visited once in contiguous chunks for any chunk and thread count;
// the exception of any chunk comes out of the loop once the chunks that started have ended;
// chunk_count follows the thread-count limit.
#include "common/parallel.hpp"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace toonwater {
namespace {

// At most `threads` threads until the test ends.
class ThreadCount {
 public:
  explicit ThreadCount(int threads)
      : limit_(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads)) {}

 private:
  tbb::global_control limit_;
};

TEST(ParallelChunks, VisitsEveryIndexOnceForAnyChunkAndThreadCount) {
  for (int threads : {1, 2, 4})
    for (std::size_t chunks : {1u, 2u, 3u, 8u})
      for (std::size_t n : {0u, 1u, 7u, 1000u}) {
        ThreadCount count(threads);
        std::vector<std::atomic<int>> visits(n);
        parallel_chunks(n, chunks, [&](std::size_t, std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
        });
        for (std::size_t i = 0; i < n; ++i)
          ASSERT_EQ(visits[i].load(), 1)
              << threads << " threads, " << chunks << " chunks, n = " << n;
      }
}

TEST(ParallelChunks, ChunkBoundariesDependOnTheChunkCountOnly) {
  const std::size_t n = 1001, chunks = 4;
  std::vector<std::vector<std::size_t>> seen;
  for (int threads : {1, 2, 4}) {
    ThreadCount count(threads);
    std::vector<std::size_t> bounds(2 * chunks);
    parallel_chunks(n, chunks, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
      bounds[2 * chunk] = begin;
      bounds[2 * chunk + 1] = end;
    });
    for (std::size_t c = 0; c < chunks; ++c) {
      EXPECT_EQ(bounds[2 * c], n * c / chunks);
      EXPECT_EQ(bounds[2 * c + 1], n * (c + 1) / chunks);
    }
    seen.push_back(bounds);
  }
  EXPECT_EQ(seen[0], seen[1]);
  EXPECT_EQ(seen[0], seen[2]);
}

TEST(ParallelChunks, ExceptionOfAnyChunkComesOutOnceTheStartedChunksEnded) {
  ThreadCount count(4);
  const std::size_t chunks = 4;
  for (std::size_t throwing = 0; throwing < chunks; ++throwing) {
    std::atomic<int> started{0}, ended{0};
    try {
      parallel_chunks(400, chunks, [&](std::size_t chunk, std::size_t, std::size_t) {
        started.fetch_add(1);
        struct End {
          std::atomic<int>& ended;
          ~End() { ended.fetch_add(1); }
        } end{ended};
        if (chunk == throwing) throw std::runtime_error("chunk " + std::to_string(chunk));
        std::this_thread::sleep_for(std::chrono::milliseconds(2));  // still running when it throws
      });
      ADD_FAILURE() << "no exception from chunk " << throwing;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "chunk " + std::to_string(throwing));
    }
    EXPECT_GE(started.load(), 1);
    EXPECT_EQ(ended.load(), started.load()) << "a chunk was still running after the loop";
  }
}

TEST(ParallelChunks, OneOfSeveralExceptionsComesOut) {
  ThreadCount count(4);
  EXPECT_THROW(parallel_chunks(100, 4,
                               [](std::size_t, std::size_t, std::size_t) {
                                 throw std::out_of_range("every chunk");
                               }),
               std::out_of_range);
}

TEST(ChunkCount, OneChunkPerThreadAndNoneSmallerThanAsked) {
  for (int threads : {1, 2, 4}) {
    ThreadCount count(threads);
    EXPECT_EQ(chunk_count(0), 1u);
    EXPECT_EQ(chunk_count(2 * serial_below - 1), 1u);
    EXPECT_EQ(chunk_count(100 * serial_below), static_cast<std::size_t>(threads));
    EXPECT_EQ(chunk_count(3000, 1000), std::min<std::size_t>(3, threads));
  }
}

TEST(ParallelChunks, NestedCallsVisitEveryIndex) {
  ThreadCount count(2);
  std::vector<std::atomic<int>> visits(64);
  parallel_chunks(4, 4, [&](std::size_t, std::size_t outer_begin, std::size_t outer_end) {
    for (std::size_t o = outer_begin; o < outer_end; ++o)
      parallel_chunks(16, 2, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) visits[o * 16 + i].fetch_add(1);
      });
  });
  for (const auto& v : visits) EXPECT_EQ(v.load(), 1);
}

}  // namespace
}  // namespace toonwater
