// Spray droplets on screen and in time; stated in spray_droplets.hpp.
#include "scene/spray_droplets.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

namespace toonwater {
namespace {

// A cell of the clustering grid: its particles' count and the sum of their positions.
struct Cell {
  std::size_t count = 0;
  Vec3 sum = Vec3::Zero();
  Vec3 velocity_sum = Vec3::Zero();
  bool taken = false;
};

// The growth of a droplet of `age` frames (0: its first), as a share of its size.
double growth(int age) {
  return std::min(1.0, 0.5 + 0.5 * age / static_cast<double>(kDropletGrowth - 1));
}

// How far (in spacings) a droplet seen once may have moved by the next frame, when neither its
// motion nor its velocity's scale is known.
constexpr double kFirstReach = 3.0;
// The droplets found again before the velocities' scale is trusted.
constexpr std::size_t kCalibrationDroplets = 8;

// How deep, in droplet sizes, a droplet found where one was expected may skim under the water.
constexpr double kSkimming = 2.0;

// When the count is capped, a droplet gathered where one was expected outranks a new one of
// up to this many times its particles: the same droplets stay drawn from frame to frame rather
// than trading places with new ones of about their size.
constexpr double kTrackedSalience = 2.0;

// A droplet drawn shrunk for the frame after it was last found.
constexpr double kFadingSize = 0.5;
// A teardrop's tail is at most this many radii long.
constexpr double kMaxTailRadii = 3.0;
// A droplet grows with the square root of its count up to this many times its size.
constexpr double kMaxDropletGrowth = 2.0;

// How deep p lies under the water, up to its surface above; 0 when it is not under it. Under:
// a ray from p straight up crosses the surface an odd number of times. That is inside for a
// closed volume and below the surface for an open one (a height field, a tank without its
// walls) alike. A crossing through an edge or a vertex shared by two faces would count twice; a
// nudge off the lattice of the simulation's cells keeps it improbable.
double depth_under_water(const SceneMesh& water, const Vec3& p) {
  const double nudge = 1e-7 * std::max(water.diagonal(), 1e-12);
  const double x = p.x() + nudge, z = p.z() + 0.61803 * nudge;
  bool inside = false;
  double nearest = std::numeric_limits<double>::infinity();
  for (const Triangle& t : water.triangles) {
    const Vec3 &a = water.positions[t[0]], &b = water.positions[t[1]], &c = water.positions[t[2]];
    if (std::max({a.y(), b.y(), c.y()}) < p.y()) continue;
    if (std::min({a.x(), b.x(), c.x()}) > x || std::max({a.x(), b.x(), c.x()}) < x ||
        std::min({a.z(), b.z(), c.z()}) > z || std::max({a.z(), b.z(), c.z()}) < z)
      continue;
    // Barycentric coordinates of (x, z) in the face's projection on the xz plane.
    const double d = (b.x() - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (b.z() - a.z());
    if (d == 0.0) continue;  // seen edge-on from below
    const double u = ((x - a.x()) * (c.z() - a.z()) - (c.x() - a.x()) * (z - a.z())) / d;
    const double v = ((b.x() - a.x()) * (z - a.z()) - (x - a.x()) * (b.z() - a.z())) / d;
    if (u < 0.0 || v < 0.0 || u + v > 1.0) continue;
    const double height = a.y() + u * (b.y() - a.y()) + v * (c.y() - a.y());
    if (height > p.y()) {
      inside = !inside;
      nearest = std::min(nearest, height);
    }
  }
  return inside ? nearest - p.y() : 0.0;
}

}  // namespace

std::vector<Droplet> spray_droplets(std::span<const Vec3> spray, const ScreenProjection& screen,
                                    const DropletOptions& options, const SceneMesh* water,
                                    std::span<const Vec3> predicted,
                                    std::span<const Vec3> velocities) {
  if (!(options.size_pixels > 0.0) || options.max_droplets == 0) return {};
  const double spacing = 2.0 * options.size_pixels;
  // The image and a margin of one cell, so droplets at its edge are whole.
  const int columns = static_cast<int>(std::ceil(screen.width / spacing)) + 2;
  const int rows = static_cast<int>(std::ceil(screen.height / spacing)) + 2;
  std::vector<Cell> cells(static_cast<std::size_t>(columns) * rows);
  const bool with_velocities = velocities.size() == spray.size();
  for (std::size_t i = 0; i < spray.size(); ++i) {
    const Vec3& p = spray[i];
    const std::optional<Eigen::Vector2d> px = screen.pixel(p);
    if (!px) continue;
    const double cx = std::floor(px->x() / spacing) + 1, cy = std::floor(px->y() / spacing) + 1;
    if (!(cx >= 0 && cx < columns && cy >= 0 && cy < rows)) continue;
    Cell& c = cells[static_cast<std::size_t>(cy) * columns + static_cast<std::size_t>(cx)];
    ++c.count;
    c.sum += p;
    if (with_velocities) c.velocity_sum += velocities[i];
  }
  // The droplet seeded at cell `seed`: the particles of its 3 × 3 block not yet taken, when
  // there are at least two.
  std::vector<Droplet> droplets;
  auto gather = [&](std::size_t seed) {
    const int sx = static_cast<int>(seed % columns), sy = static_cast<int>(seed / columns);
    std::size_t count = 0;
    for (int y = std::max(0, sy - 1); y <= std::min(rows - 1, sy + 1); ++y)
      for (int x = std::max(0, sx - 1); x <= std::min(columns - 1, sx + 1); ++x) {
        const Cell& c = cells[static_cast<std::size_t>(y) * columns + static_cast<std::size_t>(x)];
        if (!c.taken) count += c.count;
      }
    if (count < 2) return;
    Droplet d;
    Vec3 sum = Vec3::Zero(), velocity_sum = Vec3::Zero();
    for (int y = std::max(0, sy - 1); y <= std::min(rows - 1, sy + 1); ++y)
      for (int x = std::max(0, sx - 1); x <= std::min(columns - 1, sx + 1); ++x) {
        Cell& c = cells[static_cast<std::size_t>(y) * columns + static_cast<std::size_t>(x)];
        if (c.taken || c.count == 0) continue;
        c.taken = true;
        d.particles += c.count;
        sum += c.sum;
        velocity_sum += c.velocity_sum;
      }
    d.centre = sum / static_cast<double>(d.particles);
    d.velocity = velocity_sum / static_cast<double>(d.particles);
    d.tail = d.centre;
    droplets.push_back(d);
  };
  // Where the last frame's droplets are expected first, so that they are gathered again as they
  // were rather than split across the grid's cells; then the fullest cells left.
  for (std::size_t k = 0; k < predicted.size(); ++k) {
    const std::optional<Eigen::Vector2d> px = screen.pixel(predicted[k]);
    if (!px) continue;
    const double cx = std::floor(px->x() / spacing) + 1, cy = std::floor(px->y() / spacing) + 1;
    if (!(cx >= 0 && cx < columns && cy >= 0 && cy < rows)) continue;
    const std::size_t before = droplets.size();
    gather(static_cast<std::size_t>(cy) * columns + static_cast<std::size_t>(cx));
    if (droplets.size() > before) droplets.back().gathered_at = static_cast<int>(k);
  }
  std::vector<std::size_t> seeds;
  for (std::size_t i = 0; i < cells.size(); ++i)
    if (cells[i].count >= 2) seeds.push_back(i);
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](std::size_t a, std::size_t b) { return cells[a].count > cells[b].count; });
  for (const std::size_t seed : seeds)
    if (!cells[seed].taken) gather(seed);
  // Each droplet's salience: its particles, more where it was expected.
  std::vector<std::pair<double, Droplet>> ranked;
  for (std::size_t i = 0; i < droplets.size(); ++i) {
    const bool was_expected = droplets[i].gathered_at >= 0;
    if (water) {
      // A droplet found where one was expected keeps being drawn while it skims the surface,
      // up to kSkimming droplet sizes under it: spray at the crown's surface would otherwise
      // come and go as its centre crosses it. A new one must be wholly on its side.
      const double depth = depth_under_water(*water, droplets[i].centre);
      const double skimming =
          was_expected && !options.under_water
              ? kSkimming * options.size_pixels * screen.pixel_size(droplets[i].centre)
              : 0.0;
      if (!(options.under_water ? depth > 0.0 : depth <= skimming)) continue;
    }
    const double salience =
        static_cast<double>(droplets[i].particles) * (was_expected ? kTrackedSalience : 1.0);
    ranked.emplace_back(salience, droplets[i]);
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  if (ranked.size() > options.max_droplets) ranked.resize(options.max_droplets);
  droplets.clear();
  for (const auto& [salience, d] : ranked) droplets.push_back(d);
  std::stable_sort(droplets.begin(), droplets.end(),
                   [](const Droplet& a, const Droplet& b) { return a.particles > b.particles; });
  if (droplets.empty()) return droplets;

  const double median_count =
      static_cast<double>(droplets[droplets.size() / 2].particles);  // sorted, descending
  for (Droplet& d : droplets) {
    const double scale = std::clamp(std::sqrt(static_cast<double>(d.particles) / median_count), 1.0,
                                    kMaxDropletGrowth);
    d.radius = 0.5 * options.size_pixels * scale * screen.pixel_size(d.centre);
  }
  return droplets;
}

Vec3 DropletTracks::expected(const Track& track, bool& known) const {
  // Where its particles' mean velocity takes it, at the scale the sequence has shown; before
  // that scale is known, or without velocities, where its last motion takes it.
  if (calibrated_from_ >= kCalibrationDroplets && track.droplet.velocity != Vec3::Zero()) {
    known = true;
    return track.droplet.centre +
           motion_dot_velocity_ / velocity_dot_velocity_ * track.droplet.velocity;
  }
  known = track.age > 0 && track.motion != Vec3::Zero();
  return known ? Vec3(track.droplet.centre + track.motion) : track.droplet.centre;
}

std::vector<std::size_t> DropletTracks::predicted_tracks() const {
  std::vector<std::size_t> tracks;
  for (std::size_t t = 0; t < last_.size(); ++t) {
    bool known = false;
    expected(last_[t], known);
    if (known) tracks.push_back(t);
  }
  return tracks;
}

std::vector<Vec3> DropletTracks::predicted() const {
  std::vector<Vec3> places;
  for (const std::size_t t : predicted_tracks()) {
    bool known = false;
    places.push_back(expected(last_[t], known));
  }
  return places;
}

std::vector<Droplet> DropletTracks::update(std::vector<Droplet> droplets,
                                           const ScreenProjection& screen,
                                           const DropletOptions& options) {
  const double spacing = 2.0 * options.size_pixels;  // the clustering's
  // Every pair of a new droplet and a last one within reach of its predicted place: a
  // spacing, or kFirstReach spacings for a droplet whose motion is not known yet.
  std::vector<std::optional<Eigen::Vector2d>> found(droplets.size());
  for (std::size_t d = 0; d < droplets.size(); ++d) found[d] = screen.pixel(droplets[d].centre);
  // Where on screen each last droplet is expected.
  std::vector<std::optional<Eigen::Vector2d>> place(last_.size());
  for (std::size_t t = 0; t < last_.size(); ++t) {
    bool known = false;
    place[t] = screen.pixel(expected(last_[t], known));
  }
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;
  for (std::size_t t = 0; t < last_.size(); ++t) {
    if (!place[t]) continue;
    const bool moving = last_[t].age > 0 && last_[t].motion != Vec3::Zero();
    // A droplet seen once has shown no motion of its own: its place from its velocity is a
    // guess, and it keeps the wide reach.
    const double reach = moving ? spacing : kFirstReach * spacing;
    for (std::size_t d = 0; d < droplets.size(); ++d) {
      if (!found[d]) continue;
      const double distance = (*found[d] - *place[t]).norm();
      if (distance <= reach) pairs.emplace_back(distance, d, t);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<int> match(droplets.size(), -1);
  std::vector<bool> matched(last_.size(), false);
  // A droplet gathered at a last one's expected place holds the particles found there: it is
  // that droplet, when their centre lies within a spacing of the place.
  const std::vector<std::size_t> expected_tracks = predicted_tracks();
  for (std::size_t d = 0; d < droplets.size(); ++d) {
    const int k = droplets[d].gathered_at;
    if (k < 0 || static_cast<std::size_t>(k) >= expected_tracks.size() || !found[d]) continue;
    const std::size_t t = expected_tracks[static_cast<std::size_t>(k)];
    if (matched[t] || !place[t] || (*found[d] - *place[t]).norm() > spacing) continue;
    match[d] = static_cast<int>(t);
    matched[t] = true;
  }
  for (const auto& [distance, d, t] : pairs)
    if (match[d] < 0 && !matched[t]) {
      match[d] = static_cast<int>(t);
      matched[t] = true;
    }

  std::vector<Track> tracks;
  std::vector<Droplet> drawn;
  for (std::size_t d = 0; d < droplets.size(); ++d) {
    Track track;
    track.droplet = droplets[d];
    if (match[d] >= 0) {
      const Track& before = last_[static_cast<std::size_t>(match[d])];
      track.motion = droplets[d].centre - before.droplet.centre;
      track.age = before.age + 1;
      if (before.droplet.velocity != Vec3::Zero()) {
        motion_dot_velocity_ += track.motion.dot(before.droplet.velocity);
        velocity_dot_velocity_ += before.droplet.velocity.squaredNorm();
        ++calibrated_from_;
      }
    } else if (!started_) {
      track.age = kDropletGrowth;  // the first frame shows its droplets as they are
    }
    Droplet shown = track.droplet;
    shown.age = track.age;
    shown.radius *= growth(track.age);
    const double moved = track.motion.norm();
    if (moved > shown.radius)
      shown.tail =
          shown.centre - std::min(moved, kMaxTailRadii * shown.radius) / moved * track.motion;
    drawn.push_back(shown);
    tracks.push_back(track);
  }
  for (std::size_t t = 0; t < last_.size(); ++t) {
    if (matched[t]) continue;  // a fading droplet is not kept: it goes after one frame
    Droplet fading = last_[t].droplet;
    bool known = false;
    fading.centre = expected(last_[t], known);
    fading.tail = fading.centre;
    fading.fading = true;
    fading.radius *= kFadingSize * growth(last_[t].age);
    drawn.push_back(fading);
  }
  last_ = std::move(tracks);
  started_ = true;
  return drawn;
}

}  // namespace toonwater
