// Damped wave equation on a height field, the examples' water model:
//
//   ∂²h/∂t² = c² ∇²h − γ(x) ∂h/∂t + ν ∇²(∂h/∂t),
//
// h the surface elevation, c the wave speed, γ a damping rate (uniform damping, plus a sponge
// layer along the border that absorbs outgoing waves where the scene wants an open sea), ν a
// viscous (Kelvin–Voigt) damping that takes a wave of wavenumber k down at the rate ν k²: it
// removes the grid-scale ripples a centred scheme leaves behind sharp sources, and barely
// touches the long waves.
// Moving bodies enter through `displace` (body_displacement.hpp): the volume a body pushes
// below the rest level is added to h where it enters and taken where it leaves, and the wave
// equation carries it away as waves.
//
// Discretisation: five-point Laplacian with reflecting (Neumann) walls — the missing neighbour
// of a border node mirrors the node itself; semi-implicit Euler in time (velocity first, γ
// implicit, ν explicit), which is the leapfrog scheme for constant steps and is stable for
// c·Δt/Δx ≤ 1/√2 and ν·Δt/Δx² ≤ 1/4 whatever γ is.
#pragma once

#include "sim/height_field.hpp"

#include <vector>

namespace toonwater::sim {

struct WaveParameters {
  double wave_speed = 1.0;      // c
  double damping = 0.0;         // γ everywhere, 1/time
  double sponge_width = 0.0;    // width of the absorbing border (0: reflecting walls only)
  double sponge_damping = 0.0;  // extra γ at the very border, falling quadratically inwards
  double viscosity = 0.0;       // ν, length²/time
};

// γ per node for `p` on `field`'s grid.
std::vector<double> damping_per_node(const HeightField& field, const WaveParameters& p);

// The largest stable time step: half of both limits above, for a margin.
double stable_time_step(const HeightField& field, const WaveParameters& p);

// Advances `field` by `dt` (≤ stable_time_step). `damping` comes from damping_per_node.
void step_wave(HeightField& field, const WaveParameters& p, const std::vector<double>& damping,
               double dt);

// Adds `change` (per node) to the height: volume pushed in or taken out by a body.
void displace(HeightField& field, const std::vector<double>& change);

// Discrete energy per unit density: ½Σv²ΔA + ½c²Σ|∇h|²ΔA over grid edges. Without damping
// and sources it stays constant up to the scheme's bounded oscillation; with damping it decays.
double wave_energy(const HeightField& field, const WaveParameters& p);

}  // namespace toonwater::sim
