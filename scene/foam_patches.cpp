// Foam patches from foam particles; stated in foam_patches.hpp.
#include "scene/foam_patches.hpp"

#include "analyzer/point_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

namespace toonwater {
namespace {

// How far, in median edges of the water, a particle looks for the nearest vertex.
constexpr double kEdgeSearch = 2.0;

// A visible particle and the radius its foam reaches.
struct Reaching {
  Vec3 position;
  double radius;
};

// Whether a ball `reach` pixels wide around the pixel of p can show in the image.
bool reaches_image(const ScreenProjection& screen, const Vec3& p, double reach) {
  const std::optional<Eigen::Vector2d> at = screen.pixel(p);
  return at && at->x() > -reach && at->y() > -reach && at->x() < screen.width + reach &&
         at->y() < screen.height + reach;
}

// The particles summed into cells `cell` wide, in the order of their cells.
std::vector<FoamComponent> summed_in_cells(std::span<const Reaching> particles, double cell) {
  using Key = std::array<std::int64_t, 3>;
  std::vector<std::pair<Key, std::size_t>> keyed(particles.size());
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3 q = particles[i].position / cell;
    keyed[i] = {
        {static_cast<std::int64_t>(std::floor(q.x())), static_cast<std::int64_t>(std::floor(q.y())),
         static_cast<std::int64_t>(std::floor(q.z()))},
        i};
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<FoamComponent> components;
  for (std::size_t begin = 0; begin < keyed.size();) {
    std::size_t end = begin;
    Vec3 sum = Vec3::Zero();
    double radius2_sum = 0.0;
    for (; end < keyed.size() && keyed[end].first == keyed[begin].first; ++end) {
      const Reaching& r = particles[keyed[end].second];
      sum += r.position;
      radius2_sum += r.radius * r.radius;
    }
    const auto count = static_cast<double>(end - begin);
    const Vec3 centre = sum / count;
    double spread2 = 0.0;  // the particles' mean squared distance from their centre
    for (std::size_t i = begin; i < end; ++i)
      spread2 += (particles[keyed[i].second].position - centre).squaredNorm();
    spread2 /= count;
    // The kernel's mean squared reach is R²/3: matching it and the foam's amount (∝ S·R³).
    const double radius2 = radius2_sum / count;
    const double merged2 = radius2 + 3.0 * spread2;
    components.push_back({centre, std::sqrt(merged2), count * std::pow(radius2 / merged2, 1.5)});
    begin = end;
  }
  return components;
}

}  // namespace

std::vector<FoamComponent> foam_components(std::span<const Vec3> foam, const SceneMesh& water,
                                           const ScreenProjection& screen,
                                           const FoamOptions& options) {
  if (!(options.reach_pixels > 0.0) || water.positions.empty()) return {};
  std::vector<Reaching> visible;
  for (const Vec3& p : foam)
    if (reaches_image(screen, p, options.reach_pixels))
      visible.push_back({p, options.reach_pixels * screen.pixel_size(p)});
  if (visible.empty()) return {};
  std::vector<double> radii(visible.size());
  std::transform(visible.begin(), visible.end(), radii.begin(),
                 [](const Reaching& r) { return r.radius; });
  const auto middle = radii.begin() + static_cast<std::ptrdiff_t>(radii.size() / 2);
  std::nth_element(radii.begin(), middle, radii.end());
  const double median_radius = *middle;

  // Onto the surface: the tangent plane of the nearest vertex. A point of a face lies within
  // about an edge of a vertex, so the nearest one is searched kFoamSearch reaches away, or
  // kEdgeSearch median edges on a coarse mesh (not its longest edge: one huge face would put
  // every vertex in one cell of the search).
  std::vector<double> edges;
  edges.reserve(water.triangles.size());
  for (const Triangle& t : water.triangles)
    edges.push_back((water.positions[t[0]] - water.positions[t[1]]).norm());
  double median_edge = 0.0;
  if (!edges.empty()) {
    const auto half = edges.begin() + static_cast<std::ptrdiff_t>(edges.size() / 2);
    std::nth_element(edges.begin(), half, edges.end());
    median_edge = *half;
  }
  const PointGrid grid(water.positions,
                       std::max(kFoamSearch * median_radius, kEdgeSearch * median_edge));
  std::vector<Reaching> on_surface;
  on_surface.reserve(visible.size());
  for (const Reaching& r : visible) {
    const std::int32_t v = grid.closest(r.position);
    if (v < 0) continue;
    const Vec3& at = water.positions[static_cast<std::size_t>(v)];
    const Vec3& n = water.normals[static_cast<std::size_t>(v)];
    const double height = (r.position - at).dot(n);  // over the tangent plane
    if (std::abs(height) > kFoamSearch * r.radius) continue;
    on_surface.push_back({r.position - height * n, r.radius});
  }
  if (on_surface.empty()) return {};

  double cell = 0.5 * median_radius;
  std::vector<FoamComponent> components = summed_in_cells(on_surface, cell);
  while (components.size() > kMaxFoamComponents) {
    cell *= 2.0;
    components = summed_in_cells(on_surface, cell);
  }
  return components;
}

double foam_field(std::span<const FoamComponent> components, const Vec3& p) {
  double field = 0.0;
  for (const FoamComponent& c : components) {
    const double r2 = (p - c.centre).squaredNorm() / (c.radius * c.radius);
    if (r2 < 1.0) field += c.strength * (1.0 - r2) * (1.0 - r2);
  }
  return field;
}

}  // namespace toonwater
