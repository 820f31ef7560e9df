// Frames cut into ranges, for local POV-Ray processes and for farm tasks. A range is a run of
// consecutive frames: POV-Ray renders every frame between its ends (+SF/+EF), so a range never
// spans a gap. Each run of consecutive frames is cut into near-equal ranges, the first ones a
// frame longer where they cannot all be equal; only how many ranges a run is cut into differs.
#pragma once

#include "common/frame_range.hpp"

#include <string>
#include <vector>

namespace toonwater {

// For `processes` local processes: each run gets its share of them, rounded, at least one range
// and at most one range per frame. With gaps there can be more ranges than processes.
std::vector<FrameRange> ranges_for_processes(const std::vector<long>& frames, int processes);

// For farm tasks: each run in as few ranges as hold at most `per_task` frames each.
std::vector<FrameRange> ranges_of_at_most(const std::vector<long>& frames, long per_task);

// The frames of a range, in order.
std::vector<long> frames_in(const FrameRange& range);

std::string format_range(const FrameRange& range);  // "A-B"

}  // namespace toonwater
