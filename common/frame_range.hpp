// A range of frame numbers, first to last inclusive: what a scene renders (render.frames),
// what `render --frames` asks for, and what one farm task or local process renders; and the
// frames per second a scene's animation plays at (render.fps, `render --video`).
#pragma once

namespace toonwater {

// Blender's and Mantaflow's default; the frame rate of a scene that records none.
inline constexpr int default_frame_rate = 24;
inline constexpr int max_frame_rate = 240;

struct FrameRange {
  long first = 0;
  long last = 0;
};

}  // namespace toonwater
