// Strokes along narrow flow regions, contours around wide ones; stated in flow_strokes.hpp.
#include "analyzer/flow_strokes.hpp"

#include "analyzer/disjoint_sets.hpp"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <unordered_map>

namespace toonwater {
namespace {

// The region's vertices' neighbours inside it, with each edge's cost.
struct RegionGraph {
  std::vector<std::int32_t> vertices;                              // region vertex → mesh vertex
  std::vector<std::vector<std::pair<std::int32_t, double>>> next;  // → (region vertex, length)
};

// Shortest paths from `source` over the graph with edge cost cost(length, a, b).
std::vector<double> dijkstra(const RegionGraph& g, std::int32_t source,
                             const std::function<double(double, std::int32_t, std::int32_t)>& cost,
                             std::vector<std::int32_t>& previous) {
  const std::size_t n = g.vertices.size();
  std::vector<double> distance(n, std::numeric_limits<double>::infinity());
  previous.assign(n, -1);
  using Entry = std::pair<double, std::int32_t>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> open;
  distance[source] = 0.0;
  open.emplace(0.0, source);
  while (!open.empty()) {
    const auto [d, v] = open.top();
    open.pop();
    if (d > distance[v]) continue;
    for (const auto& [w, length] : g.next[v]) {
      const double through = d + cost(length, v, w);
      if (through < distance[w]) distance[w] = through, previous[w] = v, open.emplace(through, w);
    }
  }
  return distance;
}

std::int32_t farthest(const std::vector<double>& distance) {
  std::int32_t best = 0;
  for (std::size_t v = 0; v < distance.size(); ++v)
    if (std::isfinite(distance[v]) && distance[v] > distance[best])
      best = static_cast<std::int32_t>(v);
  return best;
}

// Umbrella steps along the polyline, ends held, each move without its part along `normal`.
void smooth_in_tangent_planes(std::vector<Vec3>& points, const std::vector<Vec3>& normal) {
  for (int step = 0; step < stroke_smoothing_steps; ++step) {
    std::vector<Vec3> moved = points;
    for (std::size_t i = 1; i + 1 < points.size(); ++i) {
      Vec3 move = 0.5 * (0.5 * (points[i - 1] + points[i + 1]) - points[i]);
      move -= move.dot(normal[i]) * normal[i];
      moved[i] = points[i] + move;
    }
    points = std::move(moved);
  }
}

// The vertices that share a face with v, each once.
std::vector<std::int32_t> one_ring(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                   std::int32_t v) {
  std::vector<std::int32_t> ring;
  for (std::int32_t f : vertex_faces.of(v))
    for (std::int32_t w : mesh.triangles[f])
      if (w != v) ring.push_back(w);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  return ring;
}

// How far across the crest, along `across`, the field's crest lies from vertex v: the peak of
// the parabola f(s) = a + b·s + c·s² fitted by least squares to sign·field over v and its
// one-ring, s the offset along `across`, when it opens downwards; held within half the ring's
// reach on the peak's side, beyond which a neighbour is the crest's vertex.
double crest_offset(const TriangleMesh& mesh, const std::vector<double>& field, double sign,
                    std::int32_t v, const std::vector<std::int32_t>& ring, const Vec3& across) {
  Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
  Eigen::Vector3d right = Eigen::Vector3d::Zero();
  double reach_below = 0.0, reach_above = 0.0;
  auto add = [&](double offset, double value) {
    const Eigen::Vector3d row(1.0, offset, offset * offset);
    normal_matrix += row * row.transpose();
    right += row * value;
  };
  add(0.0, sign * field[v]);
  for (std::int32_t w : ring) {
    const double offset = (mesh.positions[w] - mesh.positions[v]).dot(across);
    add(offset, sign * field[w]);
    reach_below = std::min(reach_below, offset);
    reach_above = std::max(reach_above, offset);
  }
  if (!(reach_below < 0.0 && reach_above > 0.0)) return 0.0;  // no neighbour on one side
  const Eigen::Vector3d abc = normal_matrix.ldlt().solve(right);
  if (!abc.allFinite() || !(abc[2] < 0.0)) return 0.0;
  const double peak = -abc[1] / (2.0 * abc[2]);
  return std::isfinite(peak) ? std::clamp(peak, 0.5 * reach_below, 0.5 * reach_above) : 0.0;
}

}  // namespace

std::vector<FlowLine> flow_strokes(const TriangleMesh& mesh, const VertexFaces& vertex_faces,
                                   const FlowRegions& flow, double taper_length) {
  const std::size_t n = mesh.positions.size();
  if (flow.field.size() != n || flow.label.size() != n || flow.free_surface.size() != n) return {};

  // The regions: free-surface vertices of one label joined along the edges.
  DisjointSets sets(n);
  std::vector<double> area(n, 0.0);
  for (const Triangle& t : mesh.triangles) {
    const Vec3& a = mesh.positions[t[0]];
    const double third = (mesh.positions[t[1]] - a).cross(mesh.positions[t[2]] - a).norm() / 6.0;
    for (int c = 0; c < 3; ++c) {
      area[t[c]] += third;
      const int a_v = t[c], b_v = t[(c + 1) % 3];
      if (flow.label[a_v] != FlowLabel::none && flow.label[a_v] == flow.label[b_v] &&
          flow.free_surface[a_v] && flow.free_surface[b_v])
        sets.join(a_v, b_v);
    }
  }
  std::unordered_map<std::int32_t, std::int32_t> graph_of_root;
  std::vector<RegionGraph> graphs;
  std::vector<std::int32_t> index_in_graph(n, -1), graph_of(n, -1);
  for (std::size_t v = 0; v < n; ++v) {
    if (flow.label[v] == FlowLabel::none || !flow.free_surface[v]) continue;
    const auto [it, added] = graph_of_root.try_emplace(sets.root(static_cast<std::int32_t>(v)),
                                                       static_cast<std::int32_t>(graphs.size()));
    if (added) graphs.emplace_back();
    RegionGraph& g = graphs[it->second];
    graph_of[v] = it->second;
    index_in_graph[v] = static_cast<std::int32_t>(g.vertices.size());
    g.vertices.push_back(static_cast<std::int32_t>(v));
    g.next.emplace_back();
  }
  for (const Triangle& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) {
      const int a = t[c], b = t[(c + 1) % 3];
      if (graph_of[a] < 0 || graph_of[a] != graph_of[b]) continue;
      RegionGraph& g = graphs[graph_of[a]];
      const double length = (mesh.positions[a] - mesh.positions[b]).norm();
      g.next[index_in_graph[a]].emplace_back(index_in_graph[b], length);
      g.next[index_in_graph[b]].emplace_back(index_in_graph[a], length);
    }
  // An edge inside the mesh is met from both its faces and is listed twice: the duplicate
  // neighbours do no harm to the shortest paths, and an edge on the mesh's border is met once.

  std::vector<FlowLine> lines;
  std::vector<double> wide = flow.field;  // the narrow regions taken out, for the contours
  for (const RegionGraph& g : graphs) {
    double region_area = 0.0;
    for (std::int32_t v : g.vertices) region_area += area[v];
    if (region_area < flow.min_region_area) {  // a speck, fading in or out: no stroke
      for (std::int32_t v : g.vertices) wide[v] = 0.0;
      continue;
    }
    std::vector<std::int32_t> previous;
    auto length_only = [](double length, std::int32_t, std::int32_t) { return length; };
    const std::int32_t a = farthest(dijkstra(g, 0, length_only, previous));
    const std::vector<double> from_a = dijkstra(g, a, length_only, previous);
    const std::int32_t b = farthest(from_a);
    const double spine = from_a[b];
    if (!(spine * spine >= narrow_aspect * region_area)) continue;  // wide: keeps its contour

    auto along_crest = [&](double length, std::int32_t v, std::int32_t w) {
      const double strength =
          0.5 * (std::abs(flow.field[g.vertices[v]]) + std::abs(flow.field[g.vertices[w]]));
      return length / std::max(strength, 1.0);
    };
    dijkstra(g, a, along_crest, previous);
    std::vector<std::int32_t> path;
    for (std::int32_t v = b; v >= 0; v = previous[v]) path.push_back(g.vertices[v]);
    // The ends climb onto the crest: a spine's end is often a corner of the region beside it.
    auto strength = [&](std::int32_t m) { return std::abs(flow.field[m]); };
    std::size_t first = 0, last = path.size();
    while (last - first > 2 && strength(path[first]) < strength(path[first + 1])) ++first;
    while (last - first > 2 && strength(path[last - 1]) < strength(path[last - 2])) --last;
    for (std::int32_t v : g.vertices) wide[v] = 0.0;
    if (last - first < 2) continue;
    FlowLine line;
    line.sign = flow.label[g.vertices[a]];
    const double sign = line.sign == FlowLabel::valley ? -1.0 : 1.0;
    std::vector<Vec3> normal;
    for (std::size_t i = first; i < last; ++i) {
      const std::int32_t v = path[i];
      const Vec3 n_v = flow.shading_normal.size() == n ? flow.shading_normal[v] : Vec3::Zero();
      const Vec3 along = mesh.positions[path[std::min(i + 1, last - 1)]] -
                         mesh.positions[path[std::max(i, first + 1) - 1]];
      Vec3 across = n_v.cross(along);
      Vec3 point = mesh.positions[v];
      if (across.norm() > 0.0) {
        across.normalize();
        point += crest_offset(mesh, flow.field, sign, v, one_ring(mesh, vertex_faces, v), across) *
                 across;
      }
      line.points.push_back(point);
      normal.push_back(n_v);
    }
    smooth_in_tangent_planes(line.points, normal);
    set_taper(line, taper_length);
    lines.push_back(std::move(line));
  }
  std::vector<FlowLine> contours = trace_flow_lines(mesh, wide, flow.free_surface, taper_length);
  lines.insert(lines.end(), std::make_move_iterator(contours.begin()),
               std::make_move_iterator(contours.end()));
  return lines;
}

}  // namespace toonwater
