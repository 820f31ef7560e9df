// Spray as a cartoon draws it: a frame's spray particles gathered on screen into a few
// "larger than life" droplets, and each droplet carried from frame to frame.
//
// Clustering (`spray_droplets`): every particle in front of the camera falls into a square cell
// of the image `spacing = 2 · size` pixels wide. The cells where the last frame's moving
// droplets are expected seed a droplet each first, then the fullest cell left, and so on; a
// droplet takes the particles of its cell and of the occupied cells around it (its 3 × 3
// block) not yet taken, when there are two or more. So droplets lie about a spacing apart on
// screen whatever the number of particles, a droplet sits at the mean of its particles (it
// moves smoothly as they do, not by cells), and a cell with a lone particle makes none. The
// `max_droplets` with most particles are kept: a salience order, and a bound on what a frame
// shows. A droplet is `size` pixels across at the median count of the frame's droplets,
// growing with the square root of its count up to twice that: a dense cloud reads as a big
// drop.
//
// Time (`DropletTracks`): each droplet is matched to the last frame's droplet whose predicted
// place projects nearest, greedily, nearest pairs first. The predicted place is where it was,
// moved on by its last motion, within a spacing; a droplet seen once has no motion yet (spray
// flies tens of pixels a frame), so it is looked for within three spacings, around where its
// particles' mean velocity takes it once the sequence has shown what a velocity moves a droplet
// in a frame: the scale is fitted by least squares, Δ ≈ s·v, over the droplets found again, so
// the simulation's units need not be known. A matched droplet that moved more than its own
// radius is drawn as a teardrop, its tail pointing back along the motion, at most three radii
// long. A droplet without a match is born at half its size and grows over kDropletGrowth
// frames; a droplet that finds no match is drawn once more at its predicted place, shrunk,
// then dropped: droplets come and go over a few frames instead of popping. The first frame
// shows its droplets grown.
#pragma once

#include "analyzer/mesh.hpp"
#include "scene/scene_mesh.hpp"
#include "scene/screen_projection.hpp"
#include "scene/scene_writer.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

namespace toonwater {

// A droplet in POV-Ray's frame: a sphere, and, for a teardrop, a tip behind it (tail ==
// centre: round).
struct Droplet {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  Vec3 tail = Vec3::Zero();
  std::size_t particles = 0;
  // The mean of its particles' velocities, as the simulation gives them (its units per unit of
  // its time, placed like the positions); zero when they have none.
  Vec3 velocity = Vec3::Zero();
  // From DropletTracks: the frames it was found in before this one (a first frame's droplets
  // count as grown), and whether it is a last frame's droplet drawn once more as it fades.
  int age = 0;
  bool fading = false;
  // From spray_droplets: the index in its `predicted` of the place this droplet was gathered
  // at, the continuation of the droplet expected there; −1 for a droplet seeded anew.
  int gathered_at = -1;
};

struct DropletOptions {
  double size_pixels = 8.0;
  std::size_t max_droplets = 40;
  bool under_water = false;  // keep the droplets under the water (bubbles), not those in the air
};

// Round droplets of one frame, in decreasing order of their particle counts. With `water`,
// droplets whose centre lies under it (an upward ray crosses its surface an odd number of
// times: inside a closed volume, below an open surface) are left out before the most salient
// are chosen: spray is drawn in the air, where the water's own shapes do not hide it. A
// droplet gathered where one was expected is kept while it skims the surface, up to two
// droplet sizes under it, so that spray at a crown's surface does not come and go as its
// centre crosses it. With `options.under_water` it is the other way round: bubbles are drawn
// under the water.
// `velocities`: one per particle, or none. `predicted`: where droplets are expected
// (DropletTracks::predicted), gathered first.
std::vector<Droplet> spray_droplets(std::span<const Vec3> spray, const ScreenProjection& screen,
                                    const DropletOptions& options, const SceneMesh* water = nullptr,
                                    std::span<const Vec3> predicted = {},
                                    std::span<const Vec3> velocities = {});

// The frames over which a new droplet grows to its size.
inline constexpr int kDropletGrowth = 3;

class DropletTracks {
 public:
  // This frame's droplets (from spray_droplets) matched with the last frame's: their sizes and
  // tails for drawing, and the fading ones from the last frame appended. A droplet gathered at
  // a last droplet's expected place (Droplet::gathered_at, from predicted()) continues it; the
  // others are matched to the nearest last droplets within reach of their expected places.
  std::vector<Droplet> update(std::vector<Droplet> droplets, const ScreenProjection& screen,
                              const DropletOptions& options);
  // Where the last frame's droplets are expected now, those whose place is known (their
  // particles' velocity at the fitted scale, or their last motion carried on), the most
  // particles first.
  std::vector<Vec3> predicted() const;

 private:
  struct Track {
    Droplet droplet;  // as found (full size, round)
    Vec3 motion = Vec3::Zero();
    int age = 0;
  };
  // Where a last frame's droplet is expected now, and whether that is known (its own motion,
  // or its particles' velocity once the sequence has shown what a velocity moves a droplet).
  Vec3 expected(const Track& track, bool& known) const;
  // The last droplets whose expected places predicted() gives, in its order.
  std::vector<std::size_t> predicted_tracks() const;
  std::vector<Track> last_;
  bool started_ = false;
  // The velocities' scale to a frame's motion, fitted by least squares over the droplets
  // found again: the sums of Δ·v and v·v, and how many droplets they hold.
  double motion_dot_velocity_ = 0.0, velocity_dot_velocity_ = 0.0;
  std::size_t calibrated_from_ = 0;
};

}  // namespace toonwater
