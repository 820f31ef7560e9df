// A mesh prepared for the scene from its analysis: the scene's mesh (POV-Ray frame, valid
// normals) with, as the scene draws it, the flow field and strokes or a curvature view's values.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/flow_lines.hpp"
#include "analyzer/stroke_persistence.hpp"
#include "scene/config.hpp"
#include "scene/scene_mesh.hpp"

#include <concepts>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace toonwater {

struct PreparedSurface {
  SceneMesh mesh;
  std::vector<double> flow_field;    // per vertex s (flow_regions.hpp); empty without flow regions
  std::vector<FlowLine> flow_lines;  // POV-Ray frame; only with a flow style that draws lines
  std::vector<double> view_values;   // per vertex K or H for a curvature view; else empty
  double view_range = 0;             // the sequence's colour range of view_values
  std::size_t ridge_vertices = 0, valley_vertices = 0;
  double normal_noise = 0;      // of the shading normals (flow_regions.hpp); 0: not measured
  double analysis_seconds = 0;  // its analysis and preparation, as the pipeline timed them
};

// The scene's surface from an analysis. Its normals: with `flow` (the analysis ran), the
// shading normals and their noise floor for toon shading with `normals` smoothed, the curvature
// normals for a curvature view; else angle-weighted normals of the welded, oriented surface
// (which need no more of the analysis than weld, topology and orientation) and no noise floor.
// With `flow`, as `shading` asks, the flow field and lines where flow is enabled, or the
// per-vertex K or H of a curvature view. With `persistence` (a sequence's frames in order), the
// flow strokes persist from frame to frame (stroke_persistence.hpp).
PreparedSurface prepare_surface(Analysis analysis, Axis up, const FlowConfig* flow,
                                WaterShading shading = WaterShading::toon,
                                WaterNormals normals = WaterNormals::smoothed,
                                StrokePersistence* persistence = nullptr);

// Every field of a PreparedSurface (and of the meshes and lines in it), in one list: whatever
// copies a surface field by field (the frame cache's records, pipeline/frame_record.hpp) goes
// through it. Each list unpacks its struct into exactly as many names as it has members, so a
// member added to the struct and not to its list does not compile.
template <class Line, class F>
requires std::same_as<std::remove_const_t<Line>, FlowLine>
void for_each_field(Line& line, F&& f) {
  auto& [sign, closed, points, taper] = line;
  f(sign);
  f(closed);
  f(points);
  f(taper);
}

template <class Mesh, class F>
requires std::same_as<std::remove_const_t<Mesh>, SceneMesh>
void for_each_field(Mesh& mesh, F&& f) {
  auto& [positions, normals, triangles, closed, degenerate_faces, replaced_normals, min, max] =
      mesh;
  f(positions);
  f(normals);
  f(triangles);
  f(closed);
  f(degenerate_faces);
  f(replaced_normals);
  f(min);
  f(max);
}

template <class Surface, class F>
requires std::same_as<std::remove_const_t<Surface>, PreparedSurface>
void for_each_field(Surface& s, F&& f) {
  auto& [mesh, flow_field, flow_lines, view_values, view_range, ridge_vertices, valley_vertices,
         normal_noise, analysis_seconds] = s;
  f(mesh);
  f(flow_field);
  f(flow_lines);
  f(view_values);
  f(view_range);
  f(ridge_vertices);
  f(valley_vertices);
  f(normal_noise);
  f(analysis_seconds);
}

}  // namespace toonwater
