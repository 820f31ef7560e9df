// A range of frame numbers, first to last inclusive: what a scene renders (render.frames),
// what `render --frames` asks for, and what one farm task or local process renders.
#pragma once

namespace toonwater {

struct FrameRange {
  long first = 0;
  long last = 0;
};

}  // namespace toonwater
