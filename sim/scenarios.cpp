#include "sim/scenarios.hpp"

#include "sim/mesh_builders.hpp"
#include "sim/wave_scene.hpp"
#include "sim/water_figure.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace toonwater::sim {
namespace {

constexpr int sphere_rings = 16, sphere_segments = 32;

// Runs a height-field scene; the sphere, when it moves, is written next to each water frame.
void run(const WaveScene& scene, const std::string& sphere_stem, const SimulationRequest& r,
         const MeshSink& sink, const SimulationProgress& progress) {
  run_wave_scene(scene, r.frames, [&](int frame, double time, const HeightField& field) {
    sink(frame_file_name("water", frame), height_field_mesh(field));
    if (scene.sphere)
      sink(frame_file_name(sphere_stem, frame),
           uv_sphere(scene.sphere->centre(time), scene.sphere->radius, sphere_rings,
                     sphere_segments));
    progress(frame, r.frames);
  });
}

// Open water 4 × 2; the sphere (radius 0.22, half submerged) runs along +x at 1.5 times the
// wave speed, so its waves trail in a V of half-angle asin(1/1.5) ≈ 42°. A sponge border lets
// the wake leave the picture instead of bouncing back.
void wake(const SimulationRequest& r, const MeshSink& sink, const SimulationProgress& progress) {
  WaveScene s;
  s.field = make_height_field(-2.0, 2.0, -1.0, 1.0, r.resolution);
  s.waves = {.wave_speed = 1.0,
             .damping = 0.3,
             .sponge_width = 0.4,
             .sponge_damping = 8.0,
             .viscosity = 0.006};
  s.sphere = MovingSphere{[](double t) { return Vec3(-2.0 + 1.5 * t, 0.0, 0.0); }, 0.22, 0.7};
  s.record_start = 0.6;  // the wake has formed: sphere at x = -1.1
  s.record_end = 2.2;    // sphere at x = 1.3
  run(s, "sphere", r, sink, progress);
}

// A pool 3.2 × 2 with reflecting walls; a sphere (radius 0.18) falls from y = 0.9 under
// gravity 5, enters the water and settles, floating just over half submerged, with an
// exponential slow-down that keeps its velocity continuous at the surface.
void drop(const SimulationRequest& r, const MeshSink& sink, const SimulationProgress& progress) {
  constexpr double radius = 0.18, start = 0.9, gravity = 5.0, rest = -0.02;
  const double t_hit = std::sqrt(2.0 * (start - radius) / gravity);
  const double tau = (radius - rest) / (gravity * t_hit);
  WaveScene s;
  s.field = make_height_field(-1.6, 1.6, -1.0, 1.0, r.resolution);
  s.waves = {.wave_speed = 1.0, .damping = 0.2, .viscosity = 0.004};
  s.sphere = MovingSphere{[=](double t) {
                            const double y =
                                t < t_hit ? start - 0.5 * gravity * t * t
                                          : rest + (radius - rest) * std::exp(-(t - t_hit) / tau);
                            return Vec3(0.0, y, 0.0);
                          },
                          radius, 3.0};
  s.record_start = 0.3;
  s.record_end = 1.5;
  run(s, "sphere", r, sink, progress);
}

// The pool of `drop`, disturbed at time 0 by a smooth hump near its back wall; two balls hang
// still above the water, left and right of the centre.
void reflection(const SimulationRequest& r, const MeshSink& sink,
                const SimulationProgress& progress) {
  constexpr double radius = 0.22;
  sink("left_ball.obj", uv_sphere(Vec3(-0.6, 0.35, 0.0), radius, sphere_rings, sphere_segments));
  sink("right_ball.obj", uv_sphere(Vec3(0.6, 0.35, 0.0), radius, sphere_rings, sphere_segments));
  WaveScene s;
  s.field = make_height_field(-1.6, 1.6, -1.0, 1.0, r.resolution);
  s.waves = {.wave_speed = 1.0, .damping = 0.2, .viscosity = 0.004};
  HeightField& f = s.field;
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const double dx = f.x(i) - 0.2, dz = f.z(j) - 0.6;
      f.height[f.index(i, j)] = 0.05 * std::exp(-(dx * dx + dz * dz) / (2 * 0.1 * 0.1));
    }
  s.record_start = 0.2;
  s.record_end = 1.2;
  run(s, "", r, sink, progress);
}

// The water figure over one period of its waves (the last frame is the one before the first
// repeats, so the animation loops).
void refraction(const SimulationRequest& r, const MeshSink& sink,
                const SimulationProgress& progress) {
  sink("bones.obj", water_figure_bones(r.resolution));
  const double period = water_figure_period();
  for (int frame = 1; frame <= r.frames; ++frame) {
    const double time = period * (frame - 1) / r.frames;
    sink(frame_file_name("water", frame), water_figure_body(time, r.resolution));
    progress(frame, r.frames);
  }
}

}  // namespace

const std::vector<std::string>& scenario_names() {
  static const std::vector<std::string> names{"wake", "drop", "reflection", "refraction"};
  return names;
}

int default_resolution(const std::string& scenario) { return scenario == "refraction" ? 96 : 256; }

std::string frame_file_name(const std::string& stem, int frame) {
  std::string number = std::to_string(frame);
  if (number.size() < 4) number.insert(0, 4 - number.size(), '0');
  return stem + "_" + number + ".obj";
}

void simulate(const SimulationRequest& request, const MeshSink& sink,
              const SimulationProgress& progress) {
  SimulationRequest r = request;
  if (r.resolution == 0) r.resolution = default_resolution(r.scenario);
  if (r.frames < 1) throw std::invalid_argument("simulate: --frames must be at least 1");
  if (r.resolution < 8 || r.resolution > 2048)
    throw std::invalid_argument("simulate: --resolution must be between 8 and 2048");
  if (r.scenario == "wake") return wake(r, sink, progress);
  if (r.scenario == "drop") return drop(r, sink, progress);
  if (r.scenario == "reflection") return reflection(r, sink, progress);
  if (r.scenario == "refraction") return refraction(r, sink, progress);
  throw std::invalid_argument("simulate: unknown scenario '" + r.scenario +
                              "' (wake, drop, reflection, refraction)");
}

}  // namespace toonwater::sim
