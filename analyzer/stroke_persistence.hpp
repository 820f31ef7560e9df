// Flow strokes that persist from frame to frame.
//
// Each frame's strokes are traced afresh (flow_strokes.hpp) from a field whose crests wander
// by up to a cell with the simulation's noise, so a stroke traced through the vertices jumps by
// an edge where the water barely moves, and one whose region fades vanishes at once. As lines
// are faded in and out by strength in DeCarlo et al., "Interactive rendering of suggestive
// contours with temporal coherence" (NPAR 2004), and carried from frame to frame in Kalnins et
// al., "Coherent stylized silhouettes" (SIGGRAPH 2003), the strokes of a frame are made from
// the last frame's:
//
// 1. Carry: each point of the last frame's strokes moves onto the new free surface along the
//    shading normal of its closest free-surface vertex, found within `carry_distance` median
//    edge lengths; a point with none (the water has left) is dropped, splitting its stroke.
// 2. Match: a fresh stroke takes the carried stroke of its sign that shares the most with it,
//    the larger of the shares of either's points within `match_distance` edge lengths of the
//    other, when that is at least `min_shared`; each carried stroke is taken once.
// 3. Hold still: each point q of a matched stroke moves towards its closest point c on the
//    carried one by b·(c − q), b = hold_blend · max(0, 1 − (|c − q| / (z·e))²), z =
//    `noise_distance` and e the edge length. A crest traced an edge away by noise stays where
//    it was drawn; one that moves further, as a travelling wave does, is followed as traced.
// 4. Fade: a stroke's strength s sets its drawn width (taper · s; `Toon_stroke` draws no part of it
//    under a pixel wide). A fresh stroke that matches nothing is kept but not drawn (s = 0), so one
//    that the noise traces for a single frame never shows; matched, it gains 1/fade_frames a frame
//    up to 1. The parts of a carried stroke that neither its successor (the fresh stroke matched to
//    it) covers nor another drawn stroke comes within `cover_distance` of stay where they were,
//    losing 1/fade_frames a frame until they are gone, unless held (5). The successor covers the
//    points it passes within `match_distance` of, but for those past one of its open ends by more
//    than `cover_distance`, along it or in distance beyond the end's own distance from the carried
//    stroke: moved sideways, it replaces the whole stroke; grown shorter, or no longer following a
//    bend past its end, it leaves the part past its end to fade. Strokes thus thin out where they
//    were rather than disappear or snap back, and a stroke drawn nearby does not hide one fading
//    beside it. The strokes of a sequence's first frame, which has nothing to be coherent with,
//    start at full strength.
// 5. Hold: a carried stroke is born where its region's field s reaches 1, but it lives while
//    the crest under it stands at half that, as an edge does in Canny's hysteresis ("A
//    computational approach to edge detection", PAMI 1986). One whose crest (the median of
//    sign·s at its points' closest vertices) is at least `hold_field` keeps its strength instead
//    of fading, when no drawn stroke of its sign runs beside it (within `match_distance` of
//    `min_shared` of its points: the crest is drawn already) and the salience limit
//    (FlowRegions::max_regions) has room for it beside this frame's drawn strokes, the largest
//    crest · length first. A crest that dips under the region threshold for a few frames, as
//    settling water's do, keeps its stroke instead of popping it out and in again.
#pragma once

#include "analyzer/flow_lines.hpp"
#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace toonwater {

struct StrokePersistenceOptions {
  double carry_distance = 3.0;  // in median edge lengths: farther, a point has no water under it
  double match_distance =
      3.0;                  // in median edge lengths: a point this near another stroke is shared
  double min_shared = 0.5;  // share of points near the other stroke for a match
  double cover_distance = 0.5;  // in median edge lengths: a carried point this near a drawn
                                // stroke is covered by it; farther, it fades where it was
  double noise_distance = 2.0;  // z: in median edge lengths, a move below z·e is noise
  double hold_blend = 0.9;      // weight of the carried stroke where the move is noise
  int fade_frames = 3;          // frames to fade in or out
  double hold_field = 0.5;      // s under a carried stroke at which it is held rather than faded
};

class StrokePersistence {
 public:
  explicit StrokePersistence(StrokePersistenceOptions options = {}) : options_(options) {}

  // This frame's strokes (flow_strokes on `mesh` and `flow`), made persistent with the frames
  // before: the strokes to draw, their taper times their strength. `taper_length` as given to
  // flow_strokes (a piece kept from a carried stroke tapers anew).
  std::vector<FlowLine> update(const TriangleMesh& mesh, const FlowRegions& flow,
                               std::vector<FlowLine> fresh, double taper_length);

 private:
  struct Stroke {
    FlowLine line;  // its taper: the shape at full strength
    double strength = 0.0;
    double crest = 0.0;  // carried: the median of sign·s at its points' closest vertices
  };
  std::vector<std::uint8_t> held_strokes(const std::vector<Stroke>& carried,
                                         const std::vector<Stroke>& next, std::size_t drawn,
                                         double match, std::size_t max_strokes) const;
  StrokePersistenceOptions options_;
  std::vector<Stroke> strokes_;
  bool first_frame_ = true;
};

}  // namespace toonwater
