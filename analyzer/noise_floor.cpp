// The noise floor of a smoothed field; the estimators are stated in noise_floor.hpp.
#include "analyzer/noise_floor.hpp"

#include "analyzer/curvature_smoothing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace toonwater {

namespace {
// Φ⁻¹(0.625): the lower quartile of |x| for x ~ N(0, 1).
constexpr double lower_quartile_of_unit_normal_deviation = 0.318639;
constexpr std::size_t min_members = 8;
}  // namespace

double robust_spread(std::span<const double> values, std::span<const std::uint8_t> member) {
  std::size_t members = 0;
  for (std::size_t v = 0; v < values.size(); ++v) members += member[v] != 0;
  const std::size_t stride =
      std::max<std::size_t>(1, (members + spread_samples - 1) / spread_samples);
  std::vector<double> x;
  x.reserve(members / stride + 1);
  for (std::size_t v = 0, seen = 0; v < values.size(); ++v) {
    if (!member[v]) continue;
    if (seen++ % stride == 0 && std::isfinite(values[v])) x.push_back(values[v]);
  }
  if (x.size() < min_members) return 0.0;
  auto nth = [&](double q) {
    const auto at = x.begin() + static_cast<std::ptrdiff_t>(q * static_cast<double>(x.size() - 1));
    std::nth_element(x.begin(), at, x.end());
    return *at;
  };
  const double median = nth(0.5);
  for (double& value : x) value = std::abs(value - median);
  return nth(0.25) / lower_quartile_of_unit_normal_deviation;
}

double smoothing_noise_gain(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                            std::span<const double> vertex_area,
                            std::span<const std::uint8_t> smoothed_over,
                            std::span<const std::uint8_t> member, int steps) {
  if (steps <= 0) return 1.0;
  // On a large mesh, measured on the patch of its first gain_sample_vertices vertices and the
  // faces among them: the gain is a property of the steps and the local triangulation.
  const std::size_t n = std::min(member.size(), gain_sample_vertices);
  TriangleMesh patch;
  VertexFaces patch_faces;
  const bool whole = n == member.size();
  if (!whole) {
    patch.positions.assign(mesh.positions.begin(),
                           mesh.positions.begin() + static_cast<std::ptrdiff_t>(n));
    for (const Triangle& t : mesh.triangles)
      if (static_cast<std::size_t>(std::max({t[0], t[1], t[2]})) < n) patch.triangles.push_back(t);
    patch_faces = build_vertex_faces(n, patch.triangles);
  }
  std::vector<double> white(n);
  for (std::size_t v = 0; v < n; ++v) {
    // splitmix64's finaliser of the index: a fixed, well-mixed value in [−1, 1) per vertex.
    std::uint64_t z = static_cast<std::uint64_t>(v) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    white[v] = static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
  }
  const auto in_patch = member.first(n);
  const double white_spread = robust_spread(white, in_patch);
  smooth_vertex_field(whole ? mesh : patch, whole ? vertex_faces : patch_faces,
                      vertex_area.first(n), smoothed_over.first(n), white, steps);
  return white_spread > 0.0 ? robust_spread(white, in_patch) / white_spread : 0.0;
}

double smoothed_noise_floor(std::span<const double> raw, std::span<const double> smoothed,
                            std::span<const std::uint8_t> member, double gain) {
  std::vector<double> high_pass(raw.size());
  for (std::size_t v = 0; v < raw.size(); ++v) high_pass[v] = raw[v] - smoothed[v];
  return robust_spread(high_pass, member) * gain;
}

}  // namespace toonwater
