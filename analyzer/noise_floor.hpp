// The noise floor of a per-vertex field on a simulation's surface: how far its smoothed values
// scatter where there is nothing but the simulation's noise, so that a threshold can be put
// above it (flow_regions.hpp).
//
// The spread of a set of values, robust to the waves among them:
//   spread = q₂₅(|x − median x|) / 0.3186
// For Gaussian noise the lower quartile of the absolute deviations is 0.3186 σ (Φ⁻¹(0.625)), so
// the spread is its standard deviation; the lower quartile (rather than the median absolute
// deviation) keeps to the calm part while outliers cover up to about half of the values
// (Rousseeuw and Croux, "Alternatives to the median absolute deviation", JASA 1993).
//
// The noise is told from the waves by its scale: marching cubes on a level set jitter the
// surface from vertex to vertex, while a wave spans many vertices. So the noise of the raw
// field x is the spread of its high-pass part x − S x (S the smoothing, curvature_smoothing.hpp),
// which a surface of waves alone (an FFT ocean, a sine sheet) leaves near 0, and the noise left
// in the smoothed field is that times the smoothing's gain on noise, g = spread(S w) / spread(w),
// measured on this mesh with a fixed pseudo-random field w, uniform in [−1, 1):
//   noise floor = spread(x − S x) · g.
// Waves as short as a few vertices (the chop of an FFT ocean at its grid's resolution) count as
// noise too: below the cells' scale no statistic tells them apart, and a cartoon leaves them out.
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/topology.hpp"

#include <cstdint>
#include <span>

namespace toonwater {

// The spread above over the member vertices; 0 when there are fewer than 8 members.
double robust_spread(std::span<const double> values, std::span<const std::uint8_t> member);

// The noise floor of `smoothed` = S `raw`, S being `steps` Jacobi steps over the members
// weighted by `vertex_area`.
double smoothed_noise_floor(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                            std::span<const double> vertex_area,
                            std::span<const std::uint8_t> member, std::span<const double> raw,
                            std::span<const double> smoothed, int steps);

}  // namespace toonwater
