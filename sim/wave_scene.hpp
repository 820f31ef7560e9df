// Drives the wave solver through time with a sphere moving along a path, and samples frames.
//
// Frames are taken at N evenly spaced times over [record_start, record_end] (N = 1: at the
// end). Between frames the solver takes the fewest equal steps within the stability limit,
// and after each step the water takes the change of the sphere's displacement times `gain`
// (body_displacement.hpp) — so the result depends only on the inputs: deterministic.
#pragma once

#include "analyzer/mesh.hpp"
#include "sim/height_field.hpp"
#include "sim/wave_solver.hpp"

#include <functional>
#include <optional>

namespace toonwater::sim {

struct MovingSphere {
  std::function<Vec3(double)> centre;  // position at time t (y up, rest level y = 0)
  double radius = 0;
  double gain = 1.0;  // scales the displaced volume the water takes up (> 1 exaggerates)
};

struct WaveScene {
  HeightField field;  // initial state at time 0
  WaveParameters waves;
  std::optional<MovingSphere> sphere;
  double record_start = 0, record_end = 0;
};

// Called at each frame (1 … frames) with the time and the water state.
using FrameFn = std::function<void(int frame, double time, const HeightField& field)>;

void run_wave_scene(WaveScene scene, int frames, const FrameFn& on_frame);

// Time of frame `frame` (1-based) out of `frames` over [start, end].
double frame_time(int frame, int frames, double start, double end);

}  // namespace toonwater::sim
