// Small toon islands merged into the class around them; stated in toon_islands.hpp.
#include "scene/toon_islands.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "analyzer/edge_length.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <unordered_map>

namespace toonwater {

namespace {

struct Island {
  int label = 0;
  double area = 0.0, pixels = 0.0;
  std::unordered_map<std::int32_t, std::int32_t> border;  // neighbouring island → shared edges
};

// A margin well above float's rounding of u and v (about 6e-8) and far below a class's width.
constexpr double class_margin = 1e-4;

// `x` moved to just inside (lo, hi].
float inside(float x, double lo, double hi) {
  const double margin =
      std::isfinite(hi - lo) ? std::min(class_margin, 0.25 * (hi - lo)) : class_margin;
  return static_cast<float>(std::clamp(static_cast<double>(x), lo + margin, hi - margin));
}

}  // namespace

std::size_t merge_small_islands(std::span<const Triangle> triangles, std::span<const double> area,
                                std::span<const double> pixels, std::span<const double> min_area,
                                double min_pixels, std::vector<int>& label) {
  const std::size_t n = label.size();
  if (n == 0) return 0;

  // The islands: vertices of one class joined along the edges.
  DisjointSets vertex_sets(n);
  for (const Triangle& t : triangles)
    for (int c = 0; c < 3; ++c)
      if (label[t[c]] == label[t[(c + 1) % 3]]) vertex_sets.join(t[c], t[(c + 1) % 3]);
  std::vector<std::int32_t> island_of(n, -1), island_of_root(n, -1);
  std::vector<Island> islands;
  for (const Triangle& t : triangles)
    for (int v : t) {
      if (island_of[v] >= 0) continue;
      std::int32_t& island = island_of_root[vertex_sets.root(v)];
      if (island < 0) {
        island = static_cast<std::int32_t>(islands.size());
        islands.push_back(Island{label[v], 0.0, 0.0, {}});
      }
      island_of[v] = island;
      islands[island_of[v]].area += area[v];
      islands[island_of[v]].pixels += pixels[v];
    }
  for (const Triangle& t : triangles)
    for (int c = 0; c < 3; ++c) {
      const std::int32_t a = island_of[t[c]], b = island_of[t[(c + 1) % 3]];
      if (a == b) continue;
      ++islands[a].border[b];
      ++islands[b].border[a];
    }

  // An island's size against the limits: below 1 when it is too small to keep.
  constexpr double unlimited = std::numeric_limits<double>::infinity();
  auto size_of = [&](const Island& i) {
    const double least_area = min_area[static_cast<std::size_t>(i.label)];
    return std::min(least_area > 0.0 ? i.area / least_area : unlimited,
                    min_pixels > 0.0 ? i.pixels / min_pixels : unlimited);
  };
  using Entry = std::pair<double, std::int32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> smallest;
  for (std::size_t i = 0; i < islands.size(); ++i)
    if (size_of(islands[i]) < 1.0)
      smallest.emplace(size_of(islands[i]), static_cast<std::int32_t>(i));

  DisjointSets island_sets(islands.size());
  std::size_t merges = 0;
  while (!smallest.empty()) {
    const auto [size, i] = smallest.top();
    smallest.pop();
    if (island_sets.root(i) != i || size != size_of(islands[i])) continue;  // merged or grown since
    // The neighbouring islands as they are now, with the edges shared with each.
    std::unordered_map<std::int32_t, std::int32_t> shared;
    for (const auto& [j, edges] : islands[i].border) {
      const std::int32_t r = island_sets.root(j);
      if (r != i) shared[r] += edges;
    }
    if (shared.empty()) continue;
    // The neighbour along most of the border; ties to the larger island, then the lower index.
    std::int32_t best = -1, best_edges = 0;
    for (const auto& [r, edges] : shared) {
      const bool better =
          best < 0 || edges > best_edges ||
          (edges == best_edges && (islands[r].area > islands[best].area ||
                                   (islands[r].area == islands[best].area && r < best)));
      if (better) best = r, best_edges = edges;
    }
    // The island and every neighbour of the class it joins become one island.
    Island joined{islands[best].label, islands[i].area, islands[i].pixels, {}};
    std::vector<std::int32_t> members{i};
    for (const auto& [r, edges] : shared)
      if (islands[r].label == joined.label) members.push_back(r);
    std::sort(members.begin() + 1, members.end());  // a sum in one order whatever the map's
    for (std::size_t m = 1; m < members.size(); ++m) {
      joined.area += islands[members[m]].area;
      joined.pixels += islands[members[m]].pixels;
    }
    for (std::int32_t m : members) {
      for (const auto& [j, edges] : islands[m].border) joined.border[j] += edges;
      islands[m].border.clear();
      island_sets.join(i, m);
    }
    const std::int32_t root = island_sets.root(i);
    islands[root] = std::move(joined);
    ++merges;
    if (size_of(islands[root]) < 1.0) smallest.emplace(size_of(islands[root]), root);
  }
  for (std::size_t v = 0; v < n && merges > 0; ++v)
    if (island_of[v] >= 0) label[v] = islands[island_sets.root(island_of[v])].label;
  return merges;
}

std::size_t merge_toon_islands(const SceneMesh& mesh, const Vec3& eye,
                               std::span<const double> pixel_width, const ToonLimits& limits,
                               const IslandLimits& island, std::vector<TextureCoordinate>& uv) {
  const std::size_t n = uv.size();
  const auto bands = static_cast<int>(limits.bands.size()) + 1;
  const int valley = limits.valley(), ridge = limits.ridge();
  std::vector<int> label(n);
  for (std::size_t v = 0; v < n; ++v) label[v] = toon_class(limits, uv[v]);

  // Each vertex's third of its faces' area, and in pixels that area as the camera sees it (none
  // where it faces away: the back of a sheet or a drop is hidden by its front).
  std::vector<double> area(n, 0.0), pixels(n, 0.0);
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const double third = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm() / 6.0;
    for (int v : t) area[v] += third;
  }
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3 view = eye - mesh.positions[v];
    const double distance = view.norm(), width = pixel_width[v];
    const double facing =
        distance > 0.0 ? std::max(0.0, mesh.normals[v].dot(view)) / distance : 1.0;
    pixels[v] = width > 0.0 ? area[v] * facing / (width * width) : 0.0;
  }
  const double edge = median_edge_length(mesh.positions, mesh.triangles);
  std::vector<double> min_area(static_cast<std::size_t>(ridge) + 1, 0.0);
  std::fill(min_area.begin(), min_area.begin() + bands,
            std::numbers::pi * std::pow(island.radius_edges * edge, 2));
  const std::vector<int> before = label;
  const std::size_t merges =
      merge_small_islands(mesh.triangles, area, pixels, min_area,
                          std::numbers::pi * island.radius_pixels * island.radius_pixels, label);

  constexpr double below = -std::numeric_limits<double>::infinity();
  constexpr double above = std::numeric_limits<double>::infinity();
  auto into_band = [&](float u, int b) {
    const double lo = b > 0 ? limits.bands[static_cast<std::size_t>(b) - 1] : below;
    const double hi = b < bands - 1 ? limits.bands[static_cast<std::size_t>(b)] : above;
    return inside(u, lo, hi);
  };
  for (std::size_t v = 0; v < n && merges > 0; ++v) {
    const int c = label[v];
    if (c == before[v]) continue;
    if (c == valley) {
      uv[v][1] = inside(uv[v][1], below, limits.flow->first);
    } else if (c == ridge) {
      uv[v][1] = inside(uv[v][1], limits.flow->second, above);
    } else {
      if (limits.flow) uv[v][1] = inside(uv[v][1], limits.flow->first, limits.flow->second);
      uv[v][0] = into_band(uv[v][0], c);
    }
  }

  // Under a flow region's border, the band of the water around it: an edge from a region's
  // vertex out to the bands then changes band nowhere, and no sliver of another band is drawn
  // between the region and its surroundings.
  if (!limits.flow) return merges;
  std::vector<int> around(n * static_cast<std::size_t>(bands), 0);
  for (const Triangle& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const int a = t[c], b = t[(c + 1) % 3];
      const bool a_flow = label[a] >= bands, b_flow = label[b] >= bands;
      if (a_flow && !b_flow) ++around[static_cast<std::size_t>(a) * bands + label[b]];
      if (b_flow && !a_flow) ++around[static_cast<std::size_t>(b) * bands + label[a]];
    }
  for (std::size_t v = 0; v < n; ++v) {
    if (label[v] < bands) continue;
    const auto first = around.begin() + static_cast<std::ptrdiff_t>(v * bands);
    const auto most = std::max_element(first, first + bands);
    if (*most > 0) uv[v][0] = into_band(uv[v][0], static_cast<int>(most - first));
  }
  return merges;
}

}  // namespace toonwater
