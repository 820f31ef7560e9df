// Contour tracing of the flow field; the method is stated in flow_lines.hpp.
#include "analyzer/flow_lines.hpp"

#include "analyzer/topology.hpp"

#include <algorithm>
#include <array>
#include <unordered_map>

namespace toonwater {
namespace {

// The crossings of one level and the segments between them; each crossing (an edge) belongs to
// at most two segments on a manifold surface, more only on non-manifold edges, where the chains
// simply stop.
struct Contour {
  std::vector<Vec3> crossing;
  std::vector<std::array<std::int32_t, 2>> segment_of_crossing;  // −1: none
  std::vector<std::array<std::int32_t, 2>> segments;             // crossing pairs
};

Contour level_contour(const TriangleMesh& mesh, std::span<const double> field,
                      std::span<const std::uint8_t> free_surface, double level) {
  Contour contour;
  std::unordered_map<std::uint64_t, std::int32_t> crossing_of_edge;
  const auto& s = field;
  auto inside = [&](std::int32_t v) { return level > 0 ? s[v] >= level : s[v] <= level; };
  auto crossing = [&](std::int32_t a, std::int32_t b) {
    const auto [it, added] = crossing_of_edge.try_emplace(
        edge_key(a, b), static_cast<std::int32_t>(contour.crossing.size()));
    if (added) {
      if (a > b) std::swap(a, b);  // the same point from both faces, bit for bit
      const double t = std::clamp((level - s[a]) / (s[b] - s[a]), 0.0, 1.0);
      contour.crossing.push_back(mesh.positions[a] + t * (mesh.positions[b] - mesh.positions[a]));
      contour.segment_of_crossing.push_back({-1, -1});
    }
    return it->second;
  };
  for (const Triangle& t : mesh.triangles) {
    if (!free_surface[t[0]] || !free_surface[t[1]] || !free_surface[t[2]]) continue;
    const int in = inside(t[0]) + inside(t[1]) + inside(t[2]);
    if (in == 0 || in == 3) continue;
    std::array<std::int32_t, 2> ends{};
    int found = 0;
    for (int c = 0; c < 3; ++c) {
      const std::int32_t a = t[c], b = t[(c + 1) % 3];
      if (inside(a) != inside(b)) ends[found++] = crossing(a, b);
    }
    if (ends[0] == ends[1]) continue;
    const auto index = static_cast<std::int32_t>(contour.segments.size());
    contour.segments.push_back(ends);
    for (std::int32_t e : ends) {
      auto& slots = contour.segment_of_crossing[e];
      if (slots[0] < 0)
        slots[0] = index;
      else if (slots[1] < 0)
        slots[1] = index;
    }
  }
  return contour;
}

}  // namespace

void set_taper(FlowLine& line, double taper_length) {
  const std::size_t n = line.points.size();
  line.taper.assign(n, 1.0);
  if (line.closed || n == 0) return;
  std::vector<double> along(n, 0.0);
  for (std::size_t i = 1; i < n; ++i)
    along[i] = along[i - 1] + (line.points[i] - line.points[i - 1]).norm();
  const double total = along.back();
  const double ramp = std::min(taper_length, 0.5 * total);
  for (std::size_t i = 0; i < n; ++i) {
    const double to_end = std::min(along[i], total - along[i]);
    line.taper[i] = ramp > 0.0 ? std::clamp(to_end / ramp, 0.0, 1.0) : 0.0;
  }
}

namespace {

void chain(const Contour& contour, std::int8_t sign, double taper_length,
           std::vector<FlowLine>& lines) {
  std::vector<std::uint8_t> used(contour.segments.size(), 0);
  auto other_segment = [&](std::int32_t crossing, std::int32_t from) {
    const auto& slots = contour.segment_of_crossing[crossing];
    return slots[0] == from ? slots[1] : slots[0];
  };
  auto other_end = [&](std::int32_t segment, std::int32_t crossing) {
    const auto& ends = contour.segments[segment];
    return ends[0] == crossing ? ends[1] : ends[0];
  };
  // Walks from `crossing` away from `segment`, appending crossings, until the chain ends.
  auto walk = [&](std::int32_t segment, std::int32_t crossing, std::vector<std::int32_t>& out) {
    while (true) {
      const std::int32_t next = other_segment(crossing, segment);
      if (next < 0 || used[next]) return next >= 0;  // true: came back to the start (closed)
      used[next] = 1;
      crossing = other_end(next, crossing);
      out.push_back(crossing);
      segment = next;
    }
  };
  for (std::size_t first = 0; first < contour.segments.size(); ++first) {
    if (used[first]) continue;
    used[first] = 1;
    const auto segment = static_cast<std::int32_t>(first);
    std::vector<std::int32_t> forward{contour.segments[first][0], contour.segments[first][1]};
    const bool closed = walk(segment, forward[1], forward);
    if (!closed) {
      std::vector<std::int32_t> backward;
      walk(segment, forward[0], backward);
      forward.insert(forward.begin(), backward.rbegin(), backward.rend());
    } else if (forward.size() > 2 && forward.back() == forward.front()) {
      forward.pop_back();
    }
    FlowLine line;
    line.sign = sign;
    line.closed = closed && forward.size() > 2;
    for (std::int32_t c : forward) line.points.push_back(contour.crossing[c]);
    set_taper(line, taper_length);
    lines.push_back(std::move(line));
  }
}

}  // namespace

std::vector<FlowLine> trace_flow_lines(const TriangleMesh& mesh, std::span<const double> field,
                                       std::span<const std::uint8_t> free_surface,
                                       double taper_length) {
  std::vector<FlowLine> lines;
  if (field.size() != mesh.positions.size() || free_surface.size() != mesh.positions.size())
    return lines;
  for (const std::int8_t sign : {std::int8_t{FlowLabel::ridge}, std::int8_t{FlowLabel::valley}})
    chain(level_contour(mesh, field, free_surface, static_cast<double>(sign)), sign, taper_length,
          lines);
  return lines;
}

}  // namespace toonwater
