#include "sim/wave_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace toonwater::sim {

std::vector<double> damping_per_node(const HeightField& f, const WaveParameters& p) {
  std::vector<double> gamma(f.height.size(), p.damping);
  if (p.sponge_width <= 0) return gamma;
  const double x_max = f.x(f.nx - 1), z_max = f.z(f.nz - 1);
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const double to_border =
          std::min({f.x(i) - f.x0, x_max - f.x(i), f.z(j) - f.z0, z_max - f.z(j)});
      const double depth = std::max(0.0, 1.0 - to_border / p.sponge_width);
      gamma[f.index(i, j)] += p.sponge_damping * depth * depth;
    }
  return gamma;
}

double stable_time_step(const HeightField& f, const WaveParameters& p) {
  const double waves = f.spacing / (p.wave_speed * std::sqrt(2.0));
  const double viscous = p.viscosity > 0 ? f.spacing * f.spacing / (4.0 * p.viscosity) : waves;
  return 0.5 * std::min(waves, viscous);
}

void step_wave(HeightField& f, const WaveParameters& p, const std::vector<double>& damping,
               double dt) {
  if (dt > stable_time_step(f, p) * (1 + 1e-12))
    throw std::invalid_argument("wave solver: time step above the stability limit");
  const double inv_dx2 = 1.0 / (f.spacing * f.spacing);
  const double c2 = p.wave_speed * p.wave_speed;
  const int nx = f.nx, nz = f.nz;
  const double* h = f.height.data();
  const std::vector<double> v_old = f.velocity;  // ν∇²v needs the velocities before the step
  const double* u = v_old.data();
  double* v = f.velocity.data();
  for (int j = 0; j < nz; ++j) {
    const int jm = j > 0 ? -nx : 0, jp = j + 1 < nz ? nx : 0;  // mirrored at the walls
    for (int i = 0; i < nx; ++i) {
      const int n = i + j * nx;
      const int im = i > 0 ? -1 : 0, ip = i + 1 < nx ? 1 : 0;
      const double lap_h = (h[n + im] + h[n + ip] + h[n + jm] + h[n + jp] - 4.0 * h[n]) * inv_dx2;
      const double lap_v = (u[n + im] + u[n + ip] + u[n + jm] + u[n + jp] - 4.0 * u[n]) * inv_dx2;
      v[n] = (u[n] + dt * (c2 * lap_h + p.viscosity * lap_v)) /
             (1.0 + dt * damping[static_cast<std::size_t>(n)]);
    }
  }
  for (std::size_t n = 0; n < f.height.size(); ++n) f.height[n] += dt * f.velocity[n];
}

void displace(HeightField& f, const std::vector<double>& change) {
  for (std::size_t n = 0; n < f.height.size(); ++n) f.height[n] += change[n];
}

double wave_energy(const HeightField& f, const WaveParameters& p) {
  const double c2 = p.wave_speed * p.wave_speed;
  double kinetic = 0, potential = 0;
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const std::size_t n = f.index(i, j);
      kinetic += f.velocity[n] * f.velocity[n];
      if (i + 1 < f.nx) potential += std::pow(f.height[n + 1] - f.height[n], 2);
      if (j + 1 < f.nz) potential += std::pow(f.height[f.index(i, j + 1)] - f.height[n], 2);
    }
  const double area = f.spacing * f.spacing;
  // |∇h|² ΔA summed over edges: (Δh/Δx)² Δx² = Δh².
  return 0.5 * kinetic * area + 0.5 * c2 * potential;
}

}  // namespace toonwater::sim
