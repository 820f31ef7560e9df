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
  std::vector<double> x;
  for (std::size_t v = 0; v < values.size(); ++v)
    if (member[v] && std::isfinite(values[v])) x.push_back(values[v]);
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

double smoothed_noise_floor(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                            std::span<const double> vertex_area,
                            std::span<const std::uint8_t> member, std::span<const double> raw,
                            std::span<const double> smoothed, int steps) {
  if (steps <= 0) return robust_spread(raw, member);
  const std::size_t n = raw.size();
  std::vector<double> high_pass(n), white(n), smoothed_white;
  for (std::size_t v = 0; v < n; ++v) {
    high_pass[v] = raw[v] - smoothed[v];
    // splitmix64's finaliser of the index: a fixed, well-mixed value in [−1, 1) per vertex.
    std::uint64_t z = static_cast<std::uint64_t>(v) + 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    white[v] = static_cast<double>((z ^ (z >> 31)) >> 11) * 0x1.0p-52 - 1.0;
  }
  smoothed_white = white;
  smooth_vertex_field(mesh, vertex_faces, vertex_area, member, smoothed_white, steps);
  const double white_spread = robust_spread(white, member);
  const double gain = white_spread > 0.0 ? robust_spread(smoothed_white, member) / white_spread : 0.0;
  return robust_spread(high_pass, member) * gain;
}

}  // namespace toonwater
