// What a povgen run did: each frame's work returns a FrameResult, the run's other work (static
// objects, the scene's own files, the reads and the frame cache) a RunResult, and the report is
// their sum, made in one place (summarise).
#pragma once

#include "analyzer/maps/robust_range.hpp"

#include <cstddef>
#include <string>
#include <vector>

namespace toonwater {

// Objects' includes: their mesh files read, their outline shells (written whole, shell_culling.hpp)
// and the time reading and writing them took.
struct ObjectWork {
  std::size_t reads = 0;
  std::size_t shell_faces = 0;
  double read_seconds = 0, write_seconds = 0;
  ObjectWork& operator+=(const ObjectWork& o);
};

// One frame of the sequence: its water include and its animated objects' includes.
struct FrameResult {
  long frame = 0;     // its number in the sequence
  std::string empty;  // "PATH: why" for a frame left without water (no faces); "" with water
  // The water mesh: vertices and faces as analysed, faces rendered (water.simplify).
  std::size_t vertices = 0, faces = 0, faces_kept = 0;
  std::size_t degenerate_faces = 0, replaced_normals = 0;
  std::size_t ridge_vertices = 0, valley_vertices = 0;
  std::size_t shell_faces = 0, shell_faces_kept = 0;    // the water's outline shell
  bool maps = false;                                    // its curvature maps written
  std::size_t particles = 0, droplets = 0;              // spray particles read, and droplets drawn
  std::size_t foam_particles = 0, foam_components = 0;  // foam particles read, blob components
  std::size_t bubble_particles = 0, bubbles = 0;        // bubble particles read, bubbles drawn
  // The water file read, its analysis and preparation, the render mesh's simplification, the
  // include's text and file, the maps.
  double read_seconds = 0, analysis_seconds = 0, simplify_seconds = 0, write_seconds = 0,
         maps_seconds = 0;
  ObjectWork objects;  // the animated objects' includes for this frame
};

// The run's work outside its frames.
struct RunResult {
  long first_frame = 0, last_frame = 0;  // as the scene numbers them (0 for a single frame)
  std::size_t water_reads = 0;           // water mesh files read, by the survey or the frame loop
  ObjectWork static_objects;             // their includes, each read once
  double write_seconds = 0;              // scene.pov, scene.ini and toon.inc
  std::size_t cached_frames = 0, spilled_frames = 0;
  MapRanges map_ranges;
};

struct PovgenReport {
  std::size_t frames = 0;
  long first_frame = 0, last_frame = 0;
  std::size_t vertices = 0;               // water vertices, all frames
  std::size_t faces = 0, faces_kept = 0;  // water faces, all frames: analysed, and rendered
  std::size_t degenerate_faces = 0, replaced_normals = 0;
  std::size_t shell_faces = 0,
              shell_faces_kept = 0;  // outline shells, water and objects, all frames
  std::size_t ridge_vertices = 0, valley_vertices = 0;
  std::size_t particles = 0, droplets = 0;              // spray particles read, and droplets drawn
  std::size_t foam_particles = 0, foam_components = 0;  // foam particles read, blob components
  std::size_t bubble_particles = 0, bubbles = 0;        // bubble particles read, bubbles drawn
  std::vector<std::string> empty_frames;  // "PATH: why", frames left without water (no faces)
  double read_seconds = 0, analysis_seconds = 0, simplify_seconds = 0, write_seconds = 0;
  // Water mesh files read: once per frame. Object mesh files read: once per static object,
  // once per frame for an animated one.
  std::size_t water_reads = 0, object_reads = 0;
  std::size_t cached_frames = 0, spilled_frames = 0;  // kept for the frame loop; of them on disk
  std::size_t map_frames = 0;                         // frames with maps (those with water)
  MapRanges map_ranges;                               // the maps' shared colour ranges
  double maps_seconds = 0;
  std::vector<FrameResult> per_frame;  // what the totals above are summed from, in frame order
};

// The report of a run: its frames' results summed, with the run's own work.
PovgenReport summarise(std::vector<FrameResult> frames, const RunResult& run);

}  // namespace toonwater
