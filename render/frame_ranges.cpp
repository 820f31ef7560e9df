// Runs of consecutive frames cut into near-equal ranges (see frame_ranges.hpp).
#include "render/frame_ranges.hpp"

#include <algorithm>
#include <cstddef>
#include <string>

namespace toonwater {
namespace {

// The runs of consecutive frames in `frames` (in order), each cut into `ranges_of(length)`
// near-equal ranges.
template <class RangeCount>
std::vector<FrameRange> split_runs(const std::vector<long>& frames, RangeCount ranges_of) {
  std::vector<FrameRange> runs;
  for (const long f : frames) {
    if (runs.empty() || runs.back().last != f - 1)
      runs.push_back({f, f});
    else
      runs.back().last = f;
  }
  std::vector<FrameRange> ranges;
  for (const FrameRange& run : runs) {
    const auto length = static_cast<std::size_t>(run.last - run.first + 1);
    const std::size_t count = std::clamp<std::size_t>(ranges_of(length), 1, length);
    long first = run.first;
    for (std::size_t r = 0; r < count; ++r) {
      // The first length % count ranges are one frame longer.
      const auto n = static_cast<long>(length / count + (r < length % count ? 1 : 0));
      ranges.push_back({first, first + n - 1});
      first += n;
    }
  }
  return ranges;
}

}  // namespace

std::vector<FrameRange> ranges_for_processes(const std::vector<long>& frames, int processes) {
  const std::size_t wanted = static_cast<std::size_t>(std::max(processes, 1));
  // A run's share of the processes, rounded to the nearest.
  return split_runs(frames, [&](std::size_t length) {
    return (wanted * length + frames.size() / 2) / frames.size();
  });
}

std::vector<FrameRange> ranges_of_at_most(const std::vector<long>& frames, long per_task) {
  const auto most = static_cast<std::size_t>(std::max(per_task, 1L));
  return split_runs(frames, [&](std::size_t length) { return (length + most - 1) / most; });
}

std::vector<long> frames_in(const FrameRange& range) {
  std::vector<long> frames;
  for (long f = range.first; f <= range.last; ++f) frames.push_back(f);
  return frames;
}

std::string format_range(const FrameRange& range) {
  return std::to_string(range.first) + "-" + std::to_string(range.last);
}

}  // namespace toonwater
