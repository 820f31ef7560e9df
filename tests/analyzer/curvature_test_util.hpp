// Small helpers for the curvature tests: run the pipeline stages and measure errors.
#pragma once

#include "analyzer/analysis.hpp"  // Estimator
#include "corpus/analytic_surfaces.hpp"
#include "analyzer/curvature.hpp"
#include "analyzer/curvature_jet.hpp"
#include "analyzer/topology.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace toonwater::test {

struct Curvature {
  TriangleMesh mesh;  // consistently oriented copy
  MeshTopology topology;
  CurvatureField field;
  std::size_t flipped = 0;
};

inline Curvature curvature_of(TriangleMesh mesh, Estimator estimator = Estimator::one_ring) {
  Curvature c;
  c.topology = analyze_topology(mesh);
  c.flipped = orient_consistently(mesh, c.topology);
  c.field = estimator == Estimator::one_ring ? compute_curvature(mesh, c.topology)
                                             : compute_curvature_jet(mesh, c.topology);
  c.mesh = std::move(mesh);
  return c;
}

inline Curvature jet_of(TriangleMesh mesh) { return curvature_of(std::move(mesh), Estimator::jet); }

// A flat n×n grid of unit step in the z = 0 plane, triangles counter-clockwise from +z.
inline TriangleMesh plane(int n) {
  TriangleMesh m = make_saddle(n, 0.5 * (n - 1)).mesh;
  for (Vec3& p : m.positions) p.z() = 0.0;
  return m;
}

// Splits edge {a, b} of `mesh` at a new vertex m on one side only and closes the T-junction
// with the cap (a, b, m), as marching-cubes output and mesh simplifiers leave them. The new
// vertex is displaced by `offset` from the edge's midpoint.
inline std::int32_t insert_t_junction(TriangleMesh& mesh, std::int32_t a, std::int32_t b,
                                      const Vec3& offset) {
  const auto m = static_cast<std::int32_t>(mesh.positions.size());
  mesh.positions.push_back(0.5 * (mesh.positions[a] + mesh.positions[b]) + offset);
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    Triangle& t = mesh.triangles[f];
    for (int c = 0; c < 3; ++c) {
      if (t[c] == a && t[(c + 1) % 3] == b) {  // the face traversing a→b
        const std::int32_t opposite = t[(c + 2) % 3];
        t = {a, m, opposite};
        mesh.triangles.push_back({m, b, opposite});
        mesh.triangles.push_back({a, b, m});  // the cap: angle π (or nearly) at m
        return m;
      }
    }
  }
  ADD_FAILURE() << "edge not found";
  return m;
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
  return {rms_error(c.field.gaussian, s.gaussian, s.interior,
                    k_scale > 0 ? k_scale : h_scale * h_scale),
          rms_error(c.field.mean, s.mean, s.interior, h_scale)};
}

// Vertex v's principal curvatures, from the field's K and H.
inline PrincipalCurvatures principal(const CurvatureField& f, std::size_t v) {
  return principal_curvatures(f.gaussian[v], f.mean[v]);
}

inline bool all_finite(const CurvatureField& f) {
  for (std::size_t v = 0; v < f.gaussian.size(); ++v) {
    const auto [k1, k2] = principal(f, v);
    if (!std::isfinite(f.gaussian[v]) || !std::isfinite(f.mean[v]) || !std::isfinite(k1) ||
        !std::isfinite(k2) || !std::isfinite(f.area[v]) || !f.normal[v].allFinite())
      return false;
  }
  return true;
}

}  // namespace toonwater::test
