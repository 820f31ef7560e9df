#include "pipeline/frame_result.hpp"

#include <utility>

namespace toonwater {

ObjectWork& ObjectWork::operator+=(const ObjectWork& o) {
  reads += o.reads;
  shell_faces += o.shell_faces;
  read_seconds += o.read_seconds;
  write_seconds += o.write_seconds;
  return *this;
}

PovgenReport summarise(std::vector<FrameResult> frames, const RunResult& run) {
  PovgenReport r;
  r.frames = frames.size();
  r.first_frame = run.first_frame;
  r.last_frame = run.last_frame;
  r.water_reads = run.water_reads;
  r.cached_frames = run.cached_frames;
  r.spilled_frames = run.spilled_frames;
  r.map_ranges = run.map_ranges;
  ObjectWork objects = run.static_objects;
  for (const FrameResult& f : frames) {
    if (!f.empty.empty()) r.empty_frames.push_back(f.empty);
    r.vertices += f.vertices;
    r.faces += f.faces;
    r.faces_kept += f.faces_kept;
    r.degenerate_faces += f.degenerate_faces;
    r.replaced_normals += f.replaced_normals;
    r.ridge_vertices += f.ridge_vertices;
    r.valley_vertices += f.valley_vertices;
    r.shell_faces += f.shell_faces;
    r.shell_faces_kept += f.shell_faces_kept;
    r.map_frames += f.maps ? 1 : 0;
    r.particles += f.particles;
    r.droplets += f.droplets;
    r.foam_particles += f.foam_particles;
    r.foam_components += f.foam_components;
    r.bubble_particles += f.bubble_particles;
    r.bubbles += f.bubbles;
    r.read_seconds += f.read_seconds;
    r.analysis_seconds += f.analysis_seconds;
    r.simplify_seconds += f.simplify_seconds;
    r.write_seconds += f.write_seconds;
    r.maps_seconds += f.maps_seconds;
    objects += f.objects;
  }
  // Objects' shells are written whole: every face kept.
  r.shell_faces += objects.shell_faces;
  r.shell_faces_kept += objects.shell_faces;
  r.object_reads = objects.reads;
  r.read_seconds += objects.read_seconds;
  r.write_seconds += objects.write_seconds + run.write_seconds;
  r.per_frame = std::move(frames);
  return r;
}

}  // namespace toonwater
