#include "povgen/povgen.hpp"

#include "analyzer/analysis.hpp"
#include "analyzer/atomic_file.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/topology.hpp"
#include "analyzer/vertex_normals.hpp"
#include "analyzer/weld.hpp"
#include "povgen/axes.hpp"
#include "povgen/mesh2_writer.hpp"
#include "povgen/scene_directory.hpp"
#include "povgen/scene_writer.hpp"
#include "povgen/sequence.hpp"
#include "povgen/shell_culling.hpp"
#include "povgen/simplify.hpp"
#include "povgen/stroke_writer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

namespace toonwater::povgen {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

bool is_closed(const MeshTopology& t) { return t.boundary_edges == 0 && t.nonmanifold_edges == 0; }

struct ObjectSource {
  ObjectPlacement placement;
  Sequence sequence;
};

}  // namespace

AnalyzeOptions analysis_options(const FlowConfig& flow, Axis up, WaterShading shading) {
  AnalyzeOptions options;
  options.flow.up = up;
  options.flow.criterion = flow.criterion;
  options.flow.threshold = flow.k_threshold;
  options.flow.threshold_relative = flow.k_threshold_relative;
  options.flow.smoothing_steps = flow.smoothing;
  options.flow.min_region_area = flow.min_region;
  options.estimator = flow.estimator;
  options.flow_regions = shading == WaterShading::toon;
  return options;
}

PreparedSurface prepare_surface(TriangleMesh input, Axis up, const FlowConfig* flow,
                                FlowCoherence* coherence, WaterShading shading) {
  const auto start = Clock::now();
  PreparedSurface out;
  if (flow) {
    AnalyzeOptions options = analysis_options(*flow, up, shading);
    options.coherence = shading == WaterShading::toon ? coherence : nullptr;
    Analysis a = analyze_mesh(std::move(input), options);
    out.mesh = make_scene_mesh(a.surface, a.curvature.normal, is_closed(a.topology), up);
    if (shading == WaterShading::toon) {
      if (flow->style != FlowStyle::regions) {
        // Strokes taper over 3 % of the scene's size: resolution-free, like the field.
        out.flow_lines = trace_flow_lines(a.surface, a.flow, 0.03 * a.flow.scale_length);
        for (FlowLine& line : out.flow_lines)
          for (Vec3& p : line.points) p = to_povray(p, up);
      }
      out.flow_field = std::move(a.flow.field);
      out.ridge_vertices = a.flow.ridge_vertices;
      out.valley_vertices = a.flow.valley_vertices;
    } else {
      out.view_values =
          shading == WaterShading::gaussian ? a.curvature.gaussian : a.curvature.mean;
    }
  } else {
    WeldedMesh welded = weld_coincident_vertices(std::move(input));
    const MeshTopology topology = analyze_topology(welded.mesh);
    orient_consistently(welded.mesh, topology.vertex_faces);
    const std::vector<Vec3> normals = angle_weighted_normals(welded.mesh, topology.vertex_faces);
    out.mesh = make_scene_mesh(welded.mesh, normals, is_closed(topology), up);
  }
  out.analysis_seconds = seconds_since(start);
  return out;
}

double water_line(const SceneMesh& water, const Vec3& lo, const Vec3& hi) {
  const Vec3 grow = 0.25 * (hi - lo);
  std::vector<double> heights;
  for (std::size_t v = 0; v < water.positions.size(); ++v) {
    const Vec3& p = water.positions[v];
    if (water.normals[v].y() > 0.5 && p.x() >= lo.x() - grow.x() && p.x() <= hi.x() + grow.x() &&
        p.z() >= lo.z() - grow.z() && p.z() <= hi.z() + grow.z())
      heights.push_back(p.y());
  }
  if (heights.empty()) return lo.y() - (hi - lo).norm() - 1.0;
  const auto middle = heights.begin() + static_cast<std::ptrdiff_t>(heights.size() / 2);
  std::nth_element(heights.begin(), middle, heights.end());
  return *middle;
}

std::string empty_water_include() {
  return "// Written by toonwater povgen: this frame's water mesh was empty.\n"
         "#declare Water_mesh = union {}\n"
         "#declare Water_shell = union {}\n";
}

std::vector<TextureCoordinate> texture_coordinates(const PreparedSurface& surface,
                                                   const LightGeometry& light) {
  return surface.view_values.empty()
             ? toon_coordinates(surface.mesh, light, surface.flow_field)
             : value_coordinates(surface.view_values, surface.view_range);
}

std::string mesh_include(const PreparedSurface& surface, const std::string& prefix,
                         const LightGeometry& light, std::span<const double> shell_offsets,
                         const FaceTextures* textures, const std::vector<bool>* shell_faces) {
  std::string text = "// Written by toonwater povgen: meshes for scene.pov.\n";
  const auto uv = texture_coordinates(surface, light);
  append_mesh2(text, prefix + "_mesh", surface.mesh, uv, textures);
  if (!shell_offsets.empty())
    append_shell_mesh2(text, prefix + "_shell", surface.mesh, shell_offsets, shell_faces);
  append_flow_lines(text, surface.flow_lines);
  return text;
}

PovgenReport generate_scene(const SceneConfig& config, const PovgenRequest& request,
                            const ProgressFn& progress, const std::atomic<bool>* stop) {
  Sequence water = find_sequence(request.water_pattern, request.base_dir);
  if (config.render.frames && !water.single_file) {
    auto& f = water.frames;
    // A range beyond the sequence is a mistake to report, not to clip.
    const long have_first = f.begin()->first, have_last = f.rbegin()->first;
    if (config.render.frames->first < have_first || config.render.frames->last > have_last)
      throw InputError(request.water_pattern + ": render.frames " +
                       std::to_string(config.render.frames->first) + "-" +
                       std::to_string(config.render.frames->last) +
                       " is outside the sequence's frames " + std::to_string(have_first) + "-" +
                       std::to_string(have_last));
    std::erase_if(f, [&](const auto& kv) {
      return kv.first < config.render.frames->first || kv.first > config.render.frames->last;
    });
    if (f.empty())
      throw InputError(request.water_pattern + ": no frame in render.frames " +
                       std::to_string(config.render.frames->first) + "-" +
                       std::to_string(config.render.frames->last));
  }
  // POV-Ray renders every frame number from first to last: the sequence must not have gaps.
  const long first = water.frames.begin()->first, last = water.frames.rbegin()->first;
  for (long f = first; f <= last; ++f)
    if (!water.frames.count(f))
      throw InputError(request.water_pattern + ": frame " + std::to_string(f) +
                       " is missing (frames " + std::to_string(first) + "-" +
                       std::to_string(last) + " must all exist)");

  SceneLayout layout;
  layout.config = &config;
  layout.up = request.up;
  layout.animation = water.frames.size() > 1;
  layout.first_frame = layout.animation ? first : 0;
  layout.last_frame = layout.animation ? last : 0;

  std::vector<ObjectSource> objects;
  for (const ObjectConfig& oc : config.objects) {
    ObjectSource o;
    o.placement.config = &oc;
    o.sequence = find_sequence(oc.mesh, oc.base_dir);
    o.placement.animated = !o.sequence.single_file;
    if (o.placement.animated) {
      for (const auto& [frame, path] : water.frames)
        if (!o.sequence.frames.count(frame))
          throw InputError(oc.mesh + ": object '" + oc.name + "' has no file for frame " +
                           std::to_string(frame));
    }
    objects.push_back(std::move(o));
  }

  SceneDirectory scene(request.out_dir, request.force);
  const fs::path out_dir = scene.staging();
  // A curvature view needs the analysis whether or not flow regions are drawn.
  const WaterShading shading = config.water.shading;
  const FlowConfig* flow =
      config.flow.enabled || shading != WaterShading::toon ? &config.flow : nullptr;
  const LightGeometry light = light_geometry(config.light, request.up);
  PovgenReport report;
  report.first_frame = layout.first_frame;
  report.last_frame = layout.last_frame;
  bool have_box = false;

  auto write = [&](const fs::path& name, const std::string& text) {
    const auto start = Clock::now();
    write_file_atomically(out_dir / name, text);
    report.write_seconds += seconds_since(start);
  };
  auto load = [&](const fs::path& path) {
    const auto start = Clock::now();
    InputMesh m = read_mesh(path);
    report.read_seconds += seconds_since(start);
    return m;
  };
  // A water frame in world coordinates; throws EmptyMeshError for a frame with no liquid.
  auto load_water = [&](const fs::path& path) {
    InputMesh m = load(path);
    if (request.water_transform) apply_transform(*request.water_transform, m.mesh);
    return m;
  };
  // The box of the water and objects over the sequence frames the default camera; it needs a
  // first pass over every mesh unless the camera is configured.
  bool have_scene_box = false;
  Vec3 scene_min = Vec3::Zero(), scene_max = Vec3::Zero();
  auto grow_scene_box = [&](const TriangleMesh& m) {
    for (const Vec3& position : m.positions) {
      const Vec3 p = to_povray(position, request.up);
      scene_min = have_scene_box ? Vec3(scene_min.cwiseMin(p)) : p;
      scene_max = have_scene_box ? Vec3(scene_max.cwiseMax(p)) : p;
      have_scene_box = true;
    }
  };
  if (!(config.camera.location && config.camera.look_at)) {
    for (const auto& [frame, path] : water.frames) {
      try {
        grow_scene_box(load_water(path).mesh);
      } catch (const EmptyMeshError&) {
      }
    }
    for (const ObjectSource& o : objects) {
      if (!o.placement.animated) {
        grow_scene_box(load(o.sequence.frames.begin()->second).mesh);
        continue;
      }
      for (const auto& [frame, path] : water.frames) grow_scene_box(load(o.sequence.frames.at(frame)).mesh);
    }
  }
  layout.camera = frame_camera(config, request.up, scene_min, scene_max);

  struct Box {
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();
  };
  // The shell faces written (shell_culling.hpp): empty for all of them (then the shell stays
  // closed), else a mark per face. `keep`: the faces the shell is limited to anyway.
  // `may_cull`: nothing beyond shell_culling.hpp's rule forbids culling this shell.
  auto kept_shell_faces = [&](const SceneMesh& mesh, std::span<const double> offsets,
                              bool no_reflection, bool may_cull,
                              std::span<const KeepOutBox> keep_out, const std::vector<bool>* keep) {
    std::vector<bool> kept;
    if (offsets.empty()) return kept;
    report.shell_faces += mesh.triangles.size();
    if (request.cull_shells && may_cull && shell_met_by_camera_rays_only(config, no_reflection))
      kept = shell_faces_seen_from_behind(mesh, offsets, layout.camera.location, keep_out, keep);
    else if (keep)
      kept = *keep;
    const auto count = static_cast<std::size_t>(std::count(kept.begin(), kept.end(), true));
    if (!keep && count == kept.size()) kept.clear();  // every face: the shell stays closed
    report.shell_faces_kept += kept.empty() ? mesh.triangles.size() : count;
    return kept;
  };
  std::vector<Box> object_box(objects.size());
  std::vector<KeepOutBox> keep_out(objects.size());
  std::vector<bool> submerged(objects.size(), false);
  auto write_object = [&](std::size_t i, const fs::path& path, long frame) {
    const ObjectConfig& oc = *objects[i].placement.config;
    const PreparedSurface s = prepare_surface(load(path).mesh, request.up, nullptr, nullptr);
    if (s.mesh.triangles.empty())
      throw InputError(path.string() + ": object '" + oc.name + "': all " +
                       std::to_string(s.mesh.degenerate_faces) +
                       " faces are degenerate (zero area)");
    const auto start = Clock::now();
    const std::vector<double> offsets =
        config.outline.enabled && oc.outline
            ? shell_offsets(config.outline, s.mesh, layout.camera, config.render.width)
            : std::vector<double>{};
    // An object's shell is kept whole: it is small next to the water's, and the water and other
    // objects come near it (shell_culling.hpp).
    const std::vector<bool> shell_faces =
        kept_shell_faces(s.mesh, offsets, false, /*may_cull=*/false, {}, nullptr);
    std::string text = mesh_include(s, "Obj_" + oc.name, light, offsets, nullptr,
                                    shell_faces.empty() ? nullptr : &shell_faces);
    report.write_seconds += seconds_since(start);
    write(object_include_name(oc.name, objects[i].placement.animated, frame), text);
    // The object with its shell: the water's shell faces keep away from it to be dropped.
    const double grow = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
    object_box[i] = {s.mesh.min, s.mesh.max};
    keep_out[i] = {s.mesh.min.array() - grow, s.mesh.max.array() + grow};
  };
  // Per frame, each outlined object's water line (see ObjectPlacement) when the water refracts.
  const bool refracts = shading == WaterShading::toon && config.water.transmit > 0;
  auto water_lines = [&](const SceneMesh* frame_water) {
    std::string text;
    if (!refracts || !config.outline.enabled) return text;
    for (std::size_t i = 0; i < objects.size(); ++i) {
      const ObjectConfig& oc = *objects[i].placement.config;
      if (!oc.outline) continue;
      const Box& b = object_box[i];
      const double line = frame_water ? water_line(*frame_water, b.min, b.max)
                                      : b.min.y() - (b.max - b.min).norm() - 1.0;
      submerged[i] = submerged[i] || line > b.min.y();
      text += water_line_declaration(oc.name, line);
    }
    return text;
  };

  // Static objects first.
  for (std::size_t i = 0; i < objects.size(); ++i)
    if (!objects[i].placement.animated)
      write_object(i, objects[i].sequence.frames.begin()->second, 0);

  // A curvature view's colour range is the sequence's: the 98th percentile of |value| over
  // all frames (at most 100k samples a frame), found in a first pass.
  double view_range = 0;
  if (shading != WaterShading::toon) {
    std::vector<double> magnitudes;
    for (const auto& [frame, path] : water.frames) {
      InputMesh input;
      try {
        input = load_water(path);
      } catch (const EmptyMeshError&) {
        continue;
      }
      const PreparedSurface p =
          prepare_surface(std::move(input.mesh), request.up, flow, nullptr, shading);
      const std::size_t stride = std::max<std::size_t>(1, p.view_values.size() / 100000);
      for (std::size_t v = 0; v < p.view_values.size(); v += stride)
        magnitudes.push_back(std::abs(p.view_values[v]));
    }
    if (!magnitudes.empty()) {
      const auto at = magnitudes.begin() + static_cast<std::ptrdiff_t>(
                                               0.98 * static_cast<double>(magnitudes.size() - 1));
      std::nth_element(magnitudes.begin(), at, magnitudes.end());
      view_range = *at;
    }
    if (!(view_range > 0.0)) view_range = 1.0;  // a flat surface: everything at the middle colour
  }

  // Flow regions are carried from frame to frame so they do not flicker (flow_coherence.hpp).
  FlowCoherence coherence;
  std::size_t done = 0;
  for (const auto& [frame, path] : water.frames) {
    if (stop && stop->load()) throw InterruptedError(request.out_dir.string() + ": interrupted");
    const long written_frame = layout.animation ? frame : 0;
    auto write_animated_objects = [&] {
      for (std::size_t i = 0; i < objects.size(); ++i)
        if (objects[i].placement.animated)
          write_object(i, objects[i].sequence.frames.at(frame), written_frame);
    };
    // A frame with no liquid: the scene still needs its include, with nothing in it.
    auto write_empty_frame = [&](const std::string& why) {
      if (water.frames.size() == 1) throw InputError(why);
      report.empty_frames.push_back(why);
      write_animated_objects();
      write(water_include_name(written_frame), empty_water_include() + water_lines(nullptr));
      ++report.frames;
      if (progress) progress(++done, water.frames.size());
    };
    InputMesh input;
    try {
      input = load_water(path);
    } catch (const EmptyMeshError& empty) {
      write_empty_frame(empty.what());
      continue;
    }
    const bool coherent = flow && flow->coherence && water.frames.size() > 1;
    PreparedSurface s = prepare_surface(std::move(input.mesh), request.up, flow,
                                        coherent ? &coherence : nullptr, shading);
    // POV-Ray rejects a mesh2 without faces: a frame of zero-area faces only has no water.
    if (s.mesh.triangles.empty()) {
      write_empty_frame(path.string() + ": all " + std::to_string(s.mesh.degenerate_faces) +
                        " faces are degenerate (zero area)");
      continue;
    }
    s.view_range = view_range;
    report.analysis_seconds += s.analysis_seconds;
    report.vertices += s.mesh.positions.size();
    report.degenerate_faces += s.mesh.degenerate_faces;
    report.replaced_normals += s.mesh.replaced_normals;
    report.ridge_vertices += s.ridge_vertices;
    report.valley_vertices += s.valley_vertices;
    if (s.mesh.positions.empty()) throw InputError(path.string() + ": the water mesh is empty");
    if (!have_box) {
      layout.water_min = s.mesh.min;
      layout.water_max = s.mesh.max;
      have_box = true;
    }
    layout.water_min = layout.water_min.cwiseMin(s.mesh.min);
    layout.water_max = layout.water_max.cwiseMax(s.mesh.max);

    write_animated_objects();
    report.faces += s.mesh.triangles.size();
    report.simplify_seconds +=
        simplify_water(s, light, layout, flow).seconds;
    report.faces_kept += s.mesh.triangles.size();
    const auto start = Clock::now();
    const std::vector<double> offsets =
        config.outline.enabled
            ? shell_offsets(config.outline, s.mesh, layout.camera, config.render.width)
            : std::vector<double>{};
    // A see-through closed volume (WaterBody): an opaque body gives free surface and body their
    // own textures (scene.pov); a clear one keeps the shell on the free surface only, as rays
    // refracted through the volume leave it through the floor and walls and would meet the
    // inside of a closed shell there, painting the water in the line colour.
    std::optional<FaceTextures> textures;
    std::vector<bool> upward;
    const bool see_through_volume = s.mesh.closed && refracts;
    if (see_through_volume) upward = upward_faces(s.mesh);
    if (see_through_volume && config.water.body == WaterBody::opaque) {
      layout.closed_water = true;
      textures.emplace();
      textures->names = {kWaterSurfaceTexture, kWaterBodyTexture};
      textures->index.resize(upward.size());
      for (std::size_t f = 0; f < upward.size(); ++f) textures->index[f] = upward[f] ? 0 : 1;
    }
    const bool free_surface_shell = see_through_volume && config.water.body == WaterBody::clear;
    // The water's shell is no_reflection whenever the water reflects (scene_writer.cpp).
    // Flow lines are strokes on the water, reaching up towards its shell.
    const std::vector<bool> shell_faces =
        kept_shell_faces(s.mesh, offsets, /*no_reflection=*/true, s.flow_lines.empty(), keep_out,
                         free_surface_shell ? &upward : nullptr);
    const std::string text =
        mesh_include(s, "Water", light, offsets, textures ? &*textures : nullptr,
                     shell_faces.empty() ? nullptr : &shell_faces) +
        water_lines(&s.mesh);
    report.write_seconds += seconds_since(start);
    write(water_include_name(written_frame), text);
    ++report.frames;
    if (progress) progress(++done, water.frames.size());
  }

  for (std::size_t i = 0; i < objects.size(); ++i) {
    objects[i].placement.submerged = submerged[i];
    layout.objects.push_back(objects[i].placement);
  }
  write("toon.inc", scene_toon_inc(layout));
  write("scene.ini", scene_ini(layout));
  write("scene.pov", scene_pov(layout));
  if (request.before_commit) request.before_commit();
  scene.commit();
  return report;
}

}  // namespace toonwater::povgen
