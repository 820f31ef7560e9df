// Distance from a region's border along the mesh's edges; see border_distance.hpp.
#include "analyzer/border_distance.hpp"

#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace toonwater {

std::vector<double> border_distance(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                    std::span<const std::uint8_t> member) {
  const std::size_t n = mesh.positions.size();
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::int32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
  for (std::size_t v = 0; v < n; ++v) {
    if (member[v]) continue;
    distance[v] = 0.0;
    queue.emplace(0.0, static_cast<std::int32_t>(v));
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > distance[v]) continue;  // an older, longer entry
    for (const std::int32_t f : vertex_faces.of(v)) {
      for (const std::int32_t w : mesh.triangles[f]) {
        if (w == v || !member[w]) continue;
        const double through = d + (mesh.positions[w] - mesh.positions[v]).norm();
        if (through < distance[w]) {
          distance[w] = through;
          queue.emplace(through, w);
        }
      }
    }
  }
  return distance;
}

}  // namespace toonwater
