// Frames cut into ranges (render/frame_ranges.hpp): every frame in exactly one range, in order;
// no range across a gap; farm tasks no longer than asked; local processes sharing the frames.
#include "render/frame_ranges.hpp"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

namespace toonwater {
namespace {

using Pairs = std::vector<std::pair<long, long>>;

Pairs pairs(const std::vector<FrameRange>& ranges) {
  Pairs out;
  for (const FrameRange& r : ranges) out.emplace_back(r.first, r.last);
  return out;
}

// The ranges, expanded, give back `frames`; and no range holds a frame `frames` lacks.
void expect_exact_cover(const std::vector<long>& frames, const std::vector<FrameRange>& ranges) {
  std::vector<long> covered;
  for (const FrameRange& r : ranges) {
    ASSERT_LE(r.first, r.last);
    for (const long f : frames_in(r)) covered.push_back(f);
  }
  EXPECT_EQ(covered, frames);
}

const std::vector<std::vector<long>> kFrameSets{
    {},
    {7},
    {1, 2, 3, 4, 5, 6, 7},
    {4, 6},
    {1, 2, 3, 4, 7, 8},
    {1, 2, 5},
    {1, 2, 3, 4, 5, 7, 8, 10},
    {-3, -2, -1, 0, 1, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 40}};

TEST(FrameRanges, EveryFrameInExactlyOneRangeInOrder) {
  for (const auto& frames : kFrameSets) {
    for (const int processes : {1, 2, 3, 8, 100})
      expect_exact_cover(frames, ranges_for_processes(frames, processes));
    for (const long per_task : {1L, 2L, 3L, 10L})
      expect_exact_cover(frames, ranges_of_at_most(frames, per_task));
  }
}

TEST(FrameRanges, FarmTasksHoldAtMostTheFramesAskedAndAsFewRangesAsThat) {
  for (const auto& frames : kFrameSets)
    for (const long per_task : {1L, 2L, 3L, 10L})
      for (const FrameRange& r : ranges_of_at_most(frames, per_task))
        EXPECT_LE(r.last - r.first + 1, per_task);
  EXPECT_EQ(pairs(ranges_of_at_most({1, 2, 3, 4, 5, 7, 8, 10}, 2)),
            (Pairs{{1, 2}, {3, 4}, {5, 5}, {7, 8}, {10, 10}}));
  // Seven frames at most three a task: three tasks, as equal as they can be.
  EXPECT_EQ(pairs(ranges_of_at_most({1, 2, 3, 4, 5, 6, 7}, 3)), (Pairs{{1, 3}, {4, 5}, {6, 7}}));
}

TEST(FrameRanges, LocalProcessesShareTheFramesWithoutCrossingGaps) {
  EXPECT_EQ(pairs(ranges_for_processes({1, 2, 3, 4, 5, 6, 7}, 3)), (Pairs{{1, 3}, {4, 5}, {6, 7}}));
  EXPECT_EQ(pairs(ranges_for_processes({4, 6}, 2)), (Pairs{{4, 4}, {6, 6}}));
  EXPECT_EQ(pairs(ranges_for_processes({1, 2, 3, 4, 7, 8}, 3)), (Pairs{{1, 2}, {3, 4}, {7, 8}}));
  // One process: a range per run of consecutive frames.
  EXPECT_EQ(pairs(ranges_for_processes({1, 2, 5}, 1)), (Pairs{{1, 2}, {5, 5}}));
  // Without gaps, at most one range per process.
  EXPECT_EQ(ranges_for_processes({1, 2, 3, 4, 5, 6, 7, 8, 9, 10}, 4).size(), 4u);
  EXPECT_TRUE(ranges_for_processes({}, 4).empty());
}

TEST(FrameRanges, ARangeIsWrittenAsFirstDashLast) {
  EXPECT_EQ(format_range({3, 17}), "3-17");
  EXPECT_EQ(frames_in({5, 8}), (std::vector<long>{5, 6, 7, 8}));
}

}  // namespace
}  // namespace toonwater
