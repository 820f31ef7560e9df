// Small helpers for the curvature tests: run the pipeline stages and measure errors.
#pragma once

#include "analyzer/analytic_surfaces.hpp"
#include "analyzer/curvature.hpp"
#include "analyzer/topology.hpp"

#include <cmath>
#include <vector>

namespace toonwater::test {

struct Curvature {
  TriangleMesh mesh;  // consistently oriented copy
  MeshTopology topology;
  CurvatureField field;
  std::size_t flipped = 0;
};

inline Curvature curvature_of(TriangleMesh mesh) {
  Curvature c;
  c.topology = analyze_topology(mesh);
  c.flipped = orient_consistently(mesh, c.topology.vertex_faces);
  c.field = compute_curvature(mesh, c.topology);
  c.mesh = std::move(mesh);
  return c;
}

// RMS of (estimate − exact) over the selected vertices, divided by `scale`.
inline double rms_error(const std::vector<double>& estimate, const std::vector<double>& exact,
                        const std::vector<bool>& selected, double scale) {
  double sum = 0.0;
  std::size_t n = 0;
  for (std::size_t v = 0; v < exact.size(); ++v) {
    if (!selected[v]) continue;
    sum += (estimate[v] - exact[v]) * (estimate[v] - exact[v]);
    ++n;
  }
  return std::sqrt(sum / static_cast<double>(n)) / scale;
}

inline double rms(const std::vector<double>& values, const std::vector<bool>& selected) {
  std::vector<double> zero(values.size(), 0.0);
  return rms_error(values, zero, selected, 1.0);
}

struct Errors {
  double gaussian;  // RMS error of K relative to the RMS of the exact K
  double mean;      // RMS error of H relative to the RMS of the exact H
};

inline Errors relative_errors(const AnalyticSurface& s) {
  const Curvature c = curvature_of(s.mesh);
  const double k_scale = rms(s.gaussian, s.interior);
  const double h_scale = rms(s.mean, s.interior);
  return {rms_error(c.field.gaussian, s.gaussian, s.interior, k_scale > 0 ? k_scale : h_scale * h_scale),
          rms_error(c.field.mean, s.mean, s.interior, h_scale)};
}

inline bool all_finite(const CurvatureField& f) {
  for (std::size_t v = 0; v < f.gaussian.size(); ++v)
    if (!std::isfinite(f.gaussian[v]) || !std::isfinite(f.mean[v]) || !std::isfinite(f.k1[v]) ||
        !std::isfinite(f.k2[v]) || !std::isfinite(f.area[v]) || !f.normal[v].allFinite())
      return false;
  return true;
}

}  // namespace toonwater::test
