// Strokes carried, matched, held still and faded from frame to frame; stated in
// stroke_persistence.hpp.
#include "analyzer/stroke_persistence.hpp"

#include "analyzer/point_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <tuple>

namespace toonwater {
namespace {

// The closest point to p on the line (its closing segment included when it is closed). When it
// is an open end of the line, `outward` points along the segment at that end, out past it.
struct ClosestPoint {
  Vec3 point;
  std::optional<Vec3> outward;
};

ClosestPoint closest_point(const FlowLine& line, const Vec3& p) {
  const std::vector<Vec3>& q = line.points;
  const std::size_t n = q.size();
  if (n == 1) return {q[0], std::nullopt};
  const std::size_t segments = line.closed ? n : n - 1;
  ClosestPoint best{q[0], std::nullopt};
  double best_distance2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < segments; ++i) {
    const Vec3& a = q[i];
    const Vec3 ab = q[(i + 1) % n] - a;
    const double length2 = ab.squaredNorm();
    const double t = length2 > 0.0 ? std::clamp((p - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
    const Vec3 c = a + t * ab;
    const double distance2 = (c - p).squaredNorm();
    if (distance2 < best_distance2) {
      best_distance2 = distance2;
      best = {c, std::nullopt};
      if (!line.closed && i == 0 && t == 0.0) best.outward = -ab;
      if (!line.closed && i + 1 == segments && t == 1.0) best.outward = ab;
    }
  }
  return best;
}

Vec3 closest_on(const FlowLine& line, const Vec3& p) { return closest_point(line, p).point; }

bool near(const FlowLine& line, const Vec3& p, double distance) {
  return (closest_on(line, p) - p).squaredNorm() <= distance * distance;
}

// Whether a stroke's successor covers the carried stroke's point p: it passes within `match`
// of p, and where p lies past one of its open ends E, p is no further than `beyond` past E along
// the successor and no further from E, by more than `beyond`, than E is from the carried stroke.
// A successor that has moved sideways covers the whole stroke, which it replaces; one that has
// grown shorter, or no longer follows a bend past its end, does not cover the part past its end,
// which fades where it was instead of vanishing.
bool covered_by_successor(const FlowLine& successor, const FlowLine& carried, const Vec3& p,
                          double match, double beyond) {
  const ClosestPoint c = closest_point(successor, p);
  if ((c.point - p).squaredNorm() > match * match) return false;
  if (!c.outward) return true;
  const double length = c.outward->norm();
  if (!(length > 0.0)) return true;
  const double end_shift = (closest_on(carried, c.point) - c.point).norm();
  return (p - c.point).dot(*c.outward) / length <= beyond &&
         (p - c.point).norm() <= end_shift + beyond;
}

// The share of a's points within `distance` of b.
double share_near(const FlowLine& a, const FlowLine& b, double distance) {
  std::size_t shared = 0;
  for (const Vec3& p : a.points) shared += near(b, p, distance);
  return static_cast<double>(shared) / static_cast<double>(a.points.size());
}

// The runs of kept points of `line` (keep[i]), each with at least two points; a closed line
// kept whole stays closed, and the run across its first point is one run. A piece cut from a
// line tapers anew.
std::vector<FlowLine> kept_pieces(const FlowLine& line, const std::vector<std::uint8_t>& keep,
                                  double taper_length) {
  const std::size_t n = line.points.size();
  std::vector<FlowLine> pieces;
  if (std::all_of(keep.begin(), keep.end(), [](std::uint8_t k) { return k != 0; })) {
    pieces.push_back(line);
    return pieces;
  }
  // Start after a dropped point, so that a closed line's run across its first point is whole.
  std::size_t start = 0;
  if (line.closed)
    while (keep[start]) ++start;
  FlowLine piece;
  auto finish = [&] {
    if (piece.points.size() >= 2) {
      set_taper(piece, taper_length);
      pieces.push_back(std::move(piece));
    }
    piece = FlowLine{};
    piece.sign = line.sign;
  };
  piece.sign = line.sign;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = (start + k) % n;
    if (keep[i])
      piece.points.push_back(line.points[i]);
    else
      finish();
  }
  finish();
  return pieces;
}

// The median, over the line's points, of sign·s at the closest free-surface vertex: how strongly
// the crest under a carried stroke still stands, 1 at a region's edge. 0 without a field.
double crest_under(const FlowLine& line, const PointGrid& grid,
                   const std::vector<std::int32_t>& vertex, const std::vector<double>& field) {
  std::vector<double> along;
  for (const Vec3& p : line.points) {
    const std::int32_t c = grid.closest(p);
    const std::size_t v = c < 0 ? field.size() : static_cast<std::size_t>(vertex[c]);
    along.push_back(v < field.size() ? line.sign * field[v] : 0.0);
  }
  if (along.empty()) return 0.0;
  std::nth_element(along.begin(), along.begin() + along.size() / 2, along.end());
  return along[along.size() / 2];
}

// The length of the line's polyline (its closing segment left out).
double line_length(const FlowLine& line) {
  double sum = 0.0;
  for (std::size_t i = 1; i < line.points.size(); ++i)
    sum += (line.points[i] - line.points[i - 1]).norm();
  return sum;
}

}  // namespace

std::vector<FlowLine> StrokePersistence::update(const TriangleMesh& mesh, const FlowRegions& flow,
                                                std::vector<FlowLine> fresh, double taper_length) {
  const double edge = flow.median_edge_length;
  const double step = 1.0 / std::max(1, options_.fade_frames);
  const std::size_t n = mesh.positions.size();
  std::vector<Stroke> carried;
  if (edge > 0.0 && std::isfinite(edge) && flow.free_surface.size() == n &&
      flow.shading_normal.size() == n) {
    // 1. Carry the last frame's strokes onto this frame's free surface.
    std::vector<Vec3> surface;
    std::vector<std::int32_t> vertex;
    for (std::size_t v = 0; v < n; ++v)
      if (flow.free_surface[v])
        surface.push_back(mesh.positions[v]), vertex.push_back(static_cast<std::int32_t>(v));
    if (!surface.empty() && !strokes_.empty()) {
      const PointGrid grid(surface, options_.carry_distance * edge);
      for (const Stroke& s : strokes_) {
        FlowLine moved = s.line;
        std::vector<std::uint8_t> keep(moved.points.size(), 1);
        for (std::size_t i = 0; i < moved.points.size(); ++i) {
          const std::int32_t c = grid.closest(moved.points[i]);
          if (c < 0) {
            keep[i] = 0;
            continue;
          }
          const Vec3& x = surface[c];
          const Vec3& normal = flow.shading_normal[vertex[c]];
          moved.points[i] -= normal * (moved.points[i] - x).dot(normal);
        }
        for (FlowLine& piece : kept_pieces(moved, keep, taper_length)) {
          const double crest = crest_under(piece, grid, vertex, flow.field);
          carried.push_back({std::move(piece), s.strength, crest});
        }
      }
    }
  }

  // 2. Match: the pairs that share most first, each stroke at most once.
  const double match = options_.match_distance * edge;
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // (share, fresh, carried)
  for (std::size_t i = 0; i < fresh.size(); ++i)
    for (std::size_t j = 0; j < carried.size(); ++j) {
      if (fresh[i].sign != carried[j].line.sign || fresh[i].points.empty()) continue;
      const double shared = std::max(share_near(fresh[i], carried[j].line, match),
                                     share_near(carried[j].line, fresh[i], match));
      if (shared >= options_.min_shared) pairs.emplace_back(shared, i, j);
    }
  std::stable_sort(pairs.begin(), pairs.end(),
                   [](const auto& a, const auto& b) { return std::get<0>(a) > std::get<0>(b); });
  std::vector<std::int64_t> match_of(fresh.size(), -1), successor(carried.size(), -1);
  for (const auto& [shared, i, j] : pairs) {
    if (match_of[i] >= 0 || successor[j] >= 0) continue;
    match_of[i] = static_cast<std::int64_t>(j);
    successor[j] = static_cast<std::int64_t>(i);
  }

  // 3. Hold the matched strokes still where they moved by noise; 4. fade them in.
  std::vector<Stroke> next;
  const double noise = options_.noise_distance * edge;
  for (std::size_t i = 0; i < fresh.size(); ++i) {
    Stroke s{std::move(fresh[i]), first_frame_ ? 1.0 : 0.0};
    if (match_of[i] >= 0) {
      const Stroke& before = carried[static_cast<std::size_t>(match_of[i])];
      for (Vec3& q : s.line.points) {
        const Vec3 c = closest_on(before.line, q);
        const double moved = (c - q).norm() / noise;
        q += options_.hold_blend * std::max(0.0, 1.0 - moved * moved) * (c - q);
      }
      s.strength = std::min(1.0, before.strength + step);
    }
    next.push_back(std::move(s));
  }

  // 4. Fade out what this frame's drawn strokes do not cover, but for the strokes held (5): a
  // stroke's successor covers it where they were matched, any other only where it is drawn over
  // it.
  const double cover = options_.cover_distance * edge;
  const std::size_t drawn = next.size();
  const std::vector<std::uint8_t> held =
      held_strokes(carried, next, drawn, match, flow.max_regions);
  for (std::size_t j = 0; j < carried.size(); ++j) {
    const Stroke& c = carried[j];
    const double strength = held[j] ? c.strength : c.strength - step;
    if (strength <= 0.5 * step) continue;
    std::vector<std::uint8_t> uncovered(c.line.points.size(), 1);
    for (std::size_t k = 0; k < c.line.points.size(); ++k) {
      const Vec3& p = c.line.points[k];
      for (std::size_t i = 0; i < drawn && uncovered[k]; ++i) {
        if (!(next[i].strength > 0.0) || next[i].line.sign != c.line.sign) continue;
        if (successor[j] == static_cast<std::int64_t>(i)
                ? covered_by_successor(next[i].line, c.line, p, match, cover)
                : near(next[i].line, p, cover))
          uncovered[k] = 0;
      }
    }
    for (FlowLine& piece : kept_pieces(c.line, uncovered, taper_length))
      next.push_back({std::move(piece), strength});
  }

  strokes_ = next;
  first_frame_ = false;
  std::vector<FlowLine> out;
  out.reserve(next.size());
  for (Stroke& s : next) {
    if (s.strength <= 0.0) continue;  // fresh: drawn once matched in the next frame
    for (double& t : s.line.taper) t *= s.strength;
    out.push_back(std::move(s.line));
  }
  return out;
}

// 5. Hold: the carried strokes, drawn, whose crest still stands (crest >= hold_field) and
// beside which no drawn stroke of their sign runs, the most salient first (crest times length),
// as many as the salience limit leaves room for beside this frame's drawn strokes.
std::vector<std::uint8_t> StrokePersistence::held_strokes(const std::vector<Stroke>& carried,
                                                          const std::vector<Stroke>& next,
                                                          std::size_t drawn, double match,
                                                          std::size_t max_strokes) const {
  std::vector<std::pair<double, std::size_t>> candidates;  // (salience, carried)
  for (std::size_t j = 0; j < carried.size(); ++j) {
    const Stroke& c = carried[j];
    if (!(c.strength > 0.0) || !(c.crest >= options_.hold_field)) continue;
    bool beside_drawn = false;
    for (std::size_t i = 0; i < drawn && !beside_drawn; ++i)
      beside_drawn = next[i].strength > 0.0 && next[i].line.sign == c.line.sign &&
                     share_near(c.line, next[i].line, match) >= options_.min_shared;
    if (!beside_drawn) candidates.emplace_back(c.crest * line_length(c.line), j);
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::size_t room = candidates.size();
  if (max_strokes > 0) {
    std::size_t fresh_drawn = 0;
    for (std::size_t i = 0; i < drawn; ++i) fresh_drawn += next[i].strength > 0.0;
    room = std::min(room, max_strokes > fresh_drawn ? max_strokes - fresh_drawn : 0);
  }
  std::vector<std::uint8_t> held(carried.size(), 0);
  for (std::size_t k = 0; k < room; ++k) held[candidates[k].second] = 1;
  return held;
}

}  // namespace toonwater
