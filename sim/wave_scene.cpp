#include "sim/wave_scene.hpp"

#include "sim/body_displacement.hpp"

#include <cmath>

namespace toonwater::sim {
namespace {

std::vector<double> scaled_displacement(const HeightField& f, const MovingSphere& s, double t) {
  std::vector<double> d = sphere_displacement(f, s.centre(t), s.radius);
  for (double& v : d) v *= s.gain;
  return d;
}

}  // namespace

double frame_time(int frame, int frames, double start, double end) {
  if (frames <= 1) return end;
  return start + (end - start) * static_cast<double>(frame - 1) / static_cast<double>(frames - 1);
}

void run_wave_scene(WaveScene scene, int frames, const FrameFn& on_frame) {
  HeightField& f = scene.field;
  const std::vector<double> damping = damping_per_node(f, scene.waves);
  const double max_step = stable_time_step(f, scene.waves);
  std::vector<double> displaced;
  if (scene.sphere) displaced = scaled_displacement(f, *scene.sphere, 0.0);

  double time = 0;
  for (int frame = 1; frame <= frames; ++frame) {
    const double target = frame_time(frame, frames, scene.record_start, scene.record_end);
    const double from = time, span = target - time;
    const int steps = span > 0 ? static_cast<int>(std::ceil(span / max_step)) : 0;
    for (int k = 1; k <= steps; ++k) {
      const double next = k == steps ? target : from + span * k / steps;
      step_wave(f, scene.waves, damping, next - time);
      time = next;
      if (scene.sphere) {
        std::vector<double> now = scaled_displacement(f, *scene.sphere, time);
        for (std::size_t n = 0; n < now.size(); ++n) displaced[n] = now[n] - displaced[n];
        displace(f, displaced);
        displaced = std::move(now);
      }
    }
    on_frame(frame, time, f);
  }
}

}  // namespace toonwater::sim
