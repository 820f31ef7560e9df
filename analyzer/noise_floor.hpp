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

#include <cstddef>
#include <cstdint>
#include <span>

namespace toonwater {

// The spread above over the member vertices (a deterministic sample of at most
// `spread_samples` of them, every k-th in index order: the quartiles of 65,536 values are within
// about 1 % of the whole set's); 0 when there are fewer than 8 members.
constexpr std::size_t spread_samples = std::size_t{1} << 16;
double robust_spread(std::span<const double> values, std::span<const std::uint8_t> member);

// g: the gain on noise of `steps` Jacobi steps over `smoothed_over` weighted by `vertex_area`
// (curvature_smoothing.hpp), measured with the fixed pseudo-random field at the `member`
// vertices; the same for every field smoothed by those steps, so measured once for them. On a
// mesh of more than `gain_sample_vertices` vertices, on the patch of the first ones (a mesher
// numbers its vertices in sweeps, so they are a connected piece of the surface).
constexpr std::size_t gain_sample_vertices = std::size_t{1} << 15;
double smoothing_noise_gain(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                            std::span<const double> vertex_area,
                            std::span<const std::uint8_t> smoothed_over,
                            std::span<const std::uint8_t> member, int steps);

// The noise floor of `smoothed`, the field `raw` smoothed by steps of gain `gain`.
double smoothed_noise_floor(std::span<const double> raw, std::span<const double> smoothed,
                            std::span<const std::uint8_t> member, double gain);

}  // namespace toonwater
