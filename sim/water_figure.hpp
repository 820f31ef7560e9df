// The refraction example's figure, after the paper's water dog: a closed, fish-shaped body of
// water with waves running along its flanks, and a skeleton of simple solids inside it.
//
// Body: the directions d = (sin θ cos φ, cos θ, −sin θ sin φ) of a UV sphere mapped to the
// ellipsoid with semi-axes (a, b, c) = (1, 0.5, 0.42) and scaled by
//   1 + A (1 − d_x²) sin(k x − ω t),   A = 0.06, k = 2π, ω = 3π,
// a wave travelling tail to nose that leaves nose and tail still and repeats every 2/3 s.
#pragma once

#include "analyzer/mesh.hpp"

namespace toonwater::sim {

// One period of the body's waves, in seconds.
double water_figure_period();

// The body at `time`; `segments` around, segments/2 rings from pole to pole.
TriangleMesh water_figure_body(double time, int segments);

// Skull, spine, ribs and tail bones: separate closed solids, all inside the body at any time.
TriangleMesh water_figure_bones(int segments);

}  // namespace toonwater::sim
