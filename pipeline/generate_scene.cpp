#include "pipeline/generate_scene.hpp"

#include "analyzer/analysis.hpp"
#include "common/atomic_file.hpp"
#include "analyzer/frame_source.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "analyzer/maps/top_down_map.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/particles.hpp"
#include "analyzer/stopwatch.hpp"
#include "analyzer/topology.hpp"
#include "analyzer/weld.hpp"
#include "scene/axes.hpp"
#include "scene/band_crossings.hpp"
#include "scene/droplet_writer.hpp"
#include "scene/frame_include.hpp"
#include "pipeline/frame_cache.hpp"
#include "pipeline/frame_record.hpp"
#include "scene/mesh2_writer.hpp"
#include "pipeline/scene_directory.hpp"
#include "scene/scene_writer.hpp"
#include "pipeline/sequence.hpp"
#include "scene/shell_culling.hpp"
#include "scene/simplify.hpp"
#include "scene/foam_patches.hpp"
#include "scene/foam_writer.hpp"
#include "scene/bubble_writer.hpp"
#include "scene/spray_droplets.hpp"
#include "scene/water_body.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <utility>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// Weld, topology and orientation only: what a scene without flow regions or a curvature view
// needs of a mesh (its normals are angle-weighted, prepare_surface).
Analysis geometry_analysis(TriangleMesh input) {
  Analysis a;
  a.input_vertices = input.positions.size();
  WeldedMesh welded = weld_coincident_vertices(std::move(input));
  a.surface = std::move(welded.mesh);
  a.topology = analyze_topology(a.surface);
  a.flipped_faces = orient_consistently(a.surface, a.topology);
  return a;
}

}  // namespace

AnalyzeOptions analysis_options(const FlowConfig& flow, Axis up, WaterShading shading) {
  AnalyzeOptions options = analyze_options(flow.analysis, up);
  options.flow_regions = shading == WaterShading::toon;
  return options;
}

const FlowConfig* scene_flow(const SceneConfig& config) {
  const WaterConfig& w = config.water;
  const bool geometry_only =
      w.shading == WaterShading::toon && !config.flow.enabled && w.normals == WaterNormals::mesh;
  return geometry_only ? nullptr : &config.flow;
}

std::optional<AnalyzeOptions> water_analysis(const SceneConfig& config, Axis up, bool maps) {
  if (maps) return analysis_options(config.flow, up, WaterShading::toon);
  if (!scene_flow(config)) return std::nullopt;
  return analysis_options(config.flow, up, config.water.shading);
}

PreparedSurface prepare_surface(TriangleMesh input, Axis up, const FlowConfig* flow,
                                FlowCoherence* coherence, WaterShading shading,
                                WaterNormals normals) {
  const auto start = Clock::now();
  Analysis a;
  if (flow) {
    AnalyzeOptions options = analysis_options(*flow, up, shading);
    options.coherence = shading == WaterShading::toon ? coherence : nullptr;
    a = analyze_mesh(std::move(input), options);
  } else {
    a = geometry_analysis(std::move(input));
  }
  PreparedSurface out = prepare_surface(std::move(a), up, flow, shading, normals);
  out.analysis_seconds = seconds_since(start);
  return out;
}

namespace {

// The curvature view's colour range (CurvatureRanges): every vertex, weighted by its area.
void add_view_samples(const Analysis& a, CurvatureRanges& ranges) {
  ranges.add_edge_length(a.flow.median_edge_length > 0.0 ? a.flow.median_edge_length
                                                         : median_edge_length(a.surface));
  for (std::size_t v = 0; v < a.surface.positions.size(); ++v)
    ranges.add(a.curvature.gaussian[v], a.curvature.mean[v], a.curvature.area[v]);
}

double view_range(const CurvatureRanges& ranges, WaterShading shading) {
  const MapRanges r = ranges.ranges(MapOptions{}.percentile);
  const double range = shading == WaterShading::gaussian ? r.gaussian : r.mean;
  return range > 0.0 ? range : 1.0;  // nothing measured: everything at the middle colour
}

struct ObjectSource {
  ObjectPlacement placement;
  Sequence sequence;
};

// Frame selection: the water sequence cut to render.frames. POV-Ray renders every frame number
// from first to last, so the sequence must not have gaps.
Sequence select_frames(const SceneConfig& config, const PovgenRequest& request) {
  Sequence water = find_sequence(request.water_pattern, request.base_dir);
  // A single file has no frame numbers: a range given for it would be silently ignored.
  if (config.render.frames && water.single_file)
    throw InputError(request.water_pattern + ": render.frames " +
                     std::to_string(config.render.frames->first) + "-" +
                     std::to_string(config.render.frames->last) +
                     " picks frames of a sequence, and this is a single file");
  if (config.render.frames) {
    auto& f = water.frames;
    // A range beyond the sequence is a mistake to report, not to clip.
    const long have_first = f.begin()->first, have_last = f.rbegin()->first;
    if (config.render.frames->first < have_first || config.render.frames->last > have_last)
      throw InputError(
          request.water_pattern + ": render.frames " + std::to_string(config.render.frames->first) +
          "-" + std::to_string(config.render.frames->last) + " is outside the sequence's frames " +
          std::to_string(have_first) + "-" + std::to_string(have_last));
    std::erase_if(f, [&](const auto& kv) {
      return kv.first < config.render.frames->first || kv.first > config.render.frames->last;
    });
    if (f.empty())
      throw InputError(request.water_pattern + ": no frame in render.frames " +
                       std::to_string(config.render.frames->first) + "-" +
                       std::to_string(config.render.frames->last));
  }
  const long first = water.frames.begin()->first, last = water.frames.rbegin()->first;
  for (long f = first; f <= last; ++f)
    if (!water.frames.count(f))
      throw InputError(request.water_pattern + ": frame " + std::to_string(f) +
                       " is missing (frames " + std::to_string(first) + "-" + std::to_string(last) +
                       " must all exist)");
  return water;
}

// The objects: a static object's one file, or an animated object's file for every water frame.
std::vector<ObjectSource> find_objects(const SceneConfig& config, const Sequence& water) {
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
  return objects;
}

// The particle caches: each a single file (the same every frame) or a sequence with a file for
// every water frame.
std::vector<Sequence> find_particles(const PovgenRequest& request, const Sequence& water) {
  std::vector<Sequence> caches;
  for (const std::string& pattern : request.particle_patterns) {
    Sequence cache = find_sequence(pattern, request.base_dir);
    if (!cache.single_file)
      for (const auto& [frame, path] : water.frames)
        if (!cache.frames.count(frame))
          throw InputError(pattern + ": the particles have no file for frame " +
                           std::to_string(frame));
    caches.push_back(std::move(cache));
  }
  return caches;
}

// What the frames are read for. Each water frame is read and analysed once. What the whole
// sequence shares (the box the default camera frames, the curvature view's colour range, the
// curvature maps' view and ranges) is known only after the last frame: then one pass reads and
// analyses the frames, gathers it (the survey) and keeps what writing each frame needs
// (FrameCache), and the frame loop writes them from there. Otherwise the frame loop reads,
// analyses and writes each frame in turn.
struct WaterPlan {
  const FlowConfig* flow = nullptr;  // the scene's flow settings; null: geometry only
  WaterShading shading = WaterShading::toon;
  WaterNormals normals = WaterNormals::smoothed;
  bool maps = false;
  bool camera_box = false;  // the camera is not configured
  FrameSourceOptions frames;
  bool shares() const { return camera_box || shading != WaterShading::toon || maps; }
  // The survey reads the objects for the camera's box, and keeps them for their includes (a
  // static object's mesh in SceneRun, an animated one's in each frame's record).
  bool survey_reads_objects() const { return camera_box; }
};

WaterPlan plan_water(const SceneConfig& config, const PovgenRequest& request, std::size_t frames) {
  WaterPlan plan;
  plan.flow = scene_flow(config);
  plan.shading = config.water.shading;
  plan.normals = config.water.normals;
  plan.maps = !request.maps_dir.empty();
  plan.camera_box = !(config.camera.location && config.camera.look_at);
  plan.frames.transform = request.water_transform;
  plan.frames.level_set = request.water_level_set;
  plan.frames.analysis = water_analysis(config, request.up, plan.maps);
  plan.frames.box = plan.camera_box;
  // Flow regions are carried from frame to frame so that they do not flicker
  // (flow_coherence.hpp); the maps' labels show them as the scene renders them. Coherence
  // changes only the flow field and labels: the survey's free surface and curvature are the
  // frame's own.
  plan.frames.coherent =
      config.flow.coherence &&
      (plan.maps || (plan.flow && plan.shading == WaterShading::toon && frames > 1));
  return plan;
}

// What the survey finds over the whole sequence, and what reading it took.
struct SequenceSurvey {
  bool have_box = false;
  Vec3 box_min = Vec3::Zero(), box_max = Vec3::Zero();  // POV-Ray frame
  std::vector<double> normal_noise;                     // each frame's with water
  CurvatureRanges view;                                 // the curvature view's colour range
  std::optional<MapPlanner> maps;
  // Each frame's reads (its water file, read and analysed, and its animated objects' files),
  // which the frame loop's result for it starts from.
  std::vector<FrameResult> frames;
  ObjectWork static_objects;  // the static objects' files read
  std::size_t water_reads = 0;
  void grow_box(const Vec3& lower, const Vec3& upper, Axis up) {
    const Vec3 a = to_povray(lower, up), b = to_povray(upper, up);  // a signed permutation
    box_min = have_box ? Vec3(box_min.cwiseMin(a.cwiseMin(b))) : Vec3(a.cwiseMin(b));
    box_max = have_box ? Vec3(box_max.cwiseMax(a.cwiseMax(b))) : Vec3(a.cwiseMax(b));
    have_box = true;
  }
};

template <class F>
double seconds_of(F&& work) {
  const auto start = Clock::now();
  work();
  return seconds_since(start);
}

// An object's mesh as read, and the read.
struct ObjectRead {
  TriangleMesh mesh;
  ObjectWork work;
};

// Everything one run of generate_scene shares between its steps.
struct SceneRun {
  SceneRun(const SceneConfig& c, const PovgenRequest& r, const Sequence& w)
      : config(c), request(r), water(w) {}
  const SceneConfig& config;
  const PovgenRequest& request;
  const Sequence& water;
  std::vector<ObjectSource> objects;
  WaterPlan plan;
  SceneLayout layout;
  LightGeometry light;
  fs::path out_dir;  // the staging directory
  struct Box {
    Vec3 min = Vec3::Zero(), max = Vec3::Zero();
  };
  std::vector<Box> object_box;
  std::vector<KeepOutBox> keep_out;  // each object with its shell (shell_culling.hpp)
  StrokePersistence strokes;         // the flow strokes carried from frame to frame
  std::vector<Sequence> particles;   // the particle caches (PovgenRequest::particle_patterns)
  DropletTracks droplets;            // the spray's droplets carried from frame to frame
  DropletTracks bubbles;             // the bubbles carried from frame to frame
  std::vector<bool> submerged;
  std::vector<double> contact_depth;  // each object's, in scene units (Obj_NAME_contact)
  double view_range = 0;
  std::optional<MapView> map_view;
  MapRanges map_ranges;
  bool have_water_box = false;
  // Per object, the mesh the survey read for the include written next (a static object's, or an
  // animated one's for the frame being written), taken by that include: read once, not twice.
  std::vector<std::optional<TriangleMesh>> object_mesh;

  // A file of the scene written; the seconds it took.
  double write(const fs::path& name, const std::string& text) {
    return seconds_of([&] { write_file_atomically(out_dir / name, text); });
  }
  ObjectRead read_object(const fs::path& path) {
    const auto start = Clock::now();
    InputMesh m = read_mesh(path);
    return {std::move(m.mesh), ObjectWork{.reads = 1, .read_seconds = seconds_since(start)}};
  }
  // Object i's mesh from `path`: the survey's copy where it kept one (its read counted there),
  // else read now.
  ObjectRead take_object(std::size_t i, const fs::path& path) {
    std::optional<TriangleMesh> kept = std::exchange(object_mesh[i], std::nullopt);
    return kept ? ObjectRead{std::move(*kept), {}} : read_object(path);
  }
  // A frame with water, prepared for the scene; a sequence's frames in order, so that the
  // strokes persist where the flow is coherent.
  PreparedSurface prepare(SourceFrame& f) {
    Analysis a = f.analysis ? std::move(*f.analysis) : geometry_analysis(std::move(f.mesh));
    const auto start = Clock::now();
    PreparedSurface s =
        f.analysis ? prepare_surface(std::move(a), request.up, plan.flow, plan.shading,
                                     plan.normals, plan.frames.coherent ? &strokes : nullptr)
                   : prepare_surface(std::move(a), request.up, nullptr);
    s.analysis_seconds = seconds_since(start);
    return s;
  }
};

void throw_if_stopped(const SceneRun& run, const std::atomic<bool>* stop) {
  if (stop && stop->load()) throw InterruptedError(run.request.out_dir.string() + ": interrupted");
}

// A water frame's file read and analysed: the reads of its result.
FrameResult frame_reads(const SourceFrame& f) {
  FrameResult reads;
  reads.read_seconds = f.read_seconds;
  reads.analysis_seconds = f.analysis_seconds;
  return reads;
}

// The survey, for a sequence that shares something: each water frame read and analysed once,
// what the sequence shares gathered from it, and what writing it needs kept in `cache`; with
// the default camera, the objects' meshes too, for the camera's box (read once: kept for
// their includes).
SequenceSurvey survey_sequence(SceneRun& run, FrameCache& cache, const ProgressFn& progress,
                               const std::atomic<bool>* stop) {
  SequenceSurvey survey;
  if (run.plan.maps) survey.maps.emplace(run.request.up);
  FrameSource source(run.plan.frames);
  RecordWriter record;  // one buffer for every frame's record
  const bool read_objects = run.plan.survey_reads_objects();
  auto grow = [&](const TriangleMesh& m) {
    for (const Vec3& p : m.positions) survey.grow_box(p, p, run.request.up);
  };
  for (std::size_t i = 0; read_objects && i < run.objects.size(); ++i) {
    const ObjectSource& o = run.objects[i];
    if (o.placement.animated) continue;
    ObjectRead read = run.read_object(o.sequence.frames.begin()->second);
    survey.static_objects += read.work;
    grow(read.mesh);
    run.object_mesh[i] = std::move(read.mesh);
  }
  std::size_t done = 0;
  for (const auto& [frame, path] : run.water.frames) {
    throw_if_stopped(run, stop);
    SourceFrame f = source.read(path);
    FrameResult reads = frame_reads(f);
    record.clear();
    record.string(f.empty);
    if (f.has_water()) {
      if (run.plan.camera_box) survey.grow_box(f.lower, f.upper, run.request.up);
      if (f.analysis && run.plan.shading != WaterShading::toon)
        add_view_samples(*f.analysis, survey.view);
      if (survey.maps) {
        survey.maps->add(*f.analysis);
        pack_map_inputs(record, *f.analysis);
      }
      // Its preparation time travels with it (PreparedSurface::analysis_seconds).
      const PreparedSurface prepared = run.prepare(f);
      survey.normal_noise.push_back(prepared.normal_noise);
      pack_surface(record, prepared);
    }
    for (const ObjectSource& o : run.objects) {
      if (!read_objects || !o.placement.animated) continue;
      const ObjectRead read = run.read_object(o.sequence.frames.at(frame));
      reads.objects += read.work;
      grow(read.mesh);
      mesh_fields(record, read.mesh);
    }
    cache.put(record.bytes());
    survey.frames.push_back(std::move(reads));
    if (progress) progress(PovgenPass::survey, ++done, run.water.frames.size());
  }
  survey.water_reads = source.reads();
  return survey;
}

// One object's include for a frame (0 for a static object), and its box for the water line.
// Its shell is written whole: it is small next to the water's, and the water and other objects
// come near it (shell_culling.hpp).
ObjectWork write_object(SceneRun& run, std::size_t i, const fs::path& path, long frame) {
  const ObjectConfig& oc = *run.objects[i].placement.config;
  ObjectRead read = run.take_object(i, path);
  ObjectWork work = read.work;
  const PreparedSurface s =
      prepare_surface(geometry_analysis(std::move(read.mesh)), run.request.up, nullptr);
  check_scene_extent(s.mesh, path);
  if (s.mesh.triangles.empty())
    throw InputError(path.string() + ": object '" + oc.name + "': all " +
                     std::to_string(s.mesh.degenerate_faces) + " faces are degenerate (zero area)");
  const auto start = Clock::now();
  const std::vector<double> offsets =
      run.config.outline.enabled && oc.outline
          ? shell_offsets(run.config.outline, s.mesh, run.layout.camera, run.config.render.width)
          : std::vector<double>{};
  if (!offsets.empty()) work.shell_faces = s.mesh.triangles.size();
  std::string text = mesh_include(s, "Obj_" + oc.name, texture_coordinates(s, run.light), offsets,
                                  nullptr, nullptr);
  work.write_seconds = seconds_since(start);
  work.write_seconds +=
      run.write(object_include_name(oc.name, run.objects[i].placement.animated, frame), text);
  // The object with its shell: the water's shell faces keep away from it to be dropped.
  const double grow = offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end());
  run.object_box[i] = {s.mesh.min, s.mesh.max};
  // The contact line is as wide as the outline: half of it on each side of the water.
  run.contact_depth[i] = 0.0;
  if (!offsets.empty()) {
    std::vector<double> sorted = offsets;
    const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2);
    std::nth_element(sorted.begin(), middle, sorted.end());
    run.contact_depth[i] = 0.5 * *middle;
  }
  run.keep_out[i] = {s.mesh.min.array() - grow, s.mesh.max.array() + grow};
  return work;
}

ObjectWork write_animated_objects(SceneRun& run, long frame, long written_frame) {
  ObjectWork work;
  for (std::size_t i = 0; i < run.objects.size(); ++i)
    if (run.objects[i].placement.animated)
      work += write_object(run, i, run.objects[i].sequence.frames.at(frame), written_frame);
  return work;
}

bool refracts(const SceneRun& run) {
  return run.config.water.shading == WaterShading::toon && run.config.water.transmit > 0;
}

// Per frame, each object's water (see ObjectPlacement) when the water refracts.
std::string object_waters(SceneRun& run, const SceneMesh* frame_water) {
  std::string text;
  if (!refracts(run)) return text;
  for (std::size_t i = 0; i < run.objects.size(); ++i) {
    const ObjectConfig& oc = *run.objects[i].placement.config;
    const SceneRun::Box& b = run.object_box[i];
    const double line = frame_water ? water_line(*frame_water, b.min, b.max)
                                    : b.min.y() - (b.max - b.min).norm() - 1.0;
    run.submerged[i] = run.submerged[i] || line > b.min.y();
    text += object_water_declaration(oc.name,
                                     frame_water && frame_water->closed ? frame_water : nullptr,
                                     line, run.contact_depth[i]);
  }
  return text;
}

// The sequence's water box and band limits grow with each frame that has water; the band
// limits are the sequence's from its first frame on (no survey: this frame's).
void add_to_layout(SceneRun& run, const PreparedSurface& s) {
  if (!run.have_water_box && run.layout.normal_noise == 0.0)
    run.layout.normal_noise = s.normal_noise;
  if (!run.have_water_box) {
    run.layout.water_min = s.mesh.min;
    run.layout.water_max = s.mesh.max;
    run.have_water_box = true;
  }
  run.layout.water_min = run.layout.water_min.cwiseMin(s.mesh.min);
  run.layout.water_max = run.layout.water_max.cwiseMax(s.mesh.max);
}

// A see-through closed volume (WaterBody): an opaque body gives its walls and floor their own
// textures (scene.pov); a clear one keeps the shell on the free surface only, as rays
// refracted through the volume leave it through the floor and walls and would meet the
// inside of a closed shell there, painting the water in the line colour. The faces are first
// cut where the free surface meets the body (water_body.hpp).
struct WaterBodyFaces {
  std::optional<std::vector<bool>> body;         // an opaque body: its walls and floor
  std::optional<std::vector<bool>> shell_limit;  // a clear body: the faces its shell keeps to
};

WaterBodyFaces water_body_faces(const SceneRun& run, PreparedSurface& s,
                                std::vector<TextureCoordinate>& uv) {
  WaterBodyFaces out;
  if (!(s.mesh.closed && refracts(run))) return out;
  std::vector<bool> upward = cut_free_surface_from_body(s, uv);
  if (run.config.water.body == WaterBody::opaque) {
    std::vector<bool> walls_and_floor = std::move(upward);
    walls_and_floor.flip();
    out.body = std::move(walls_and_floor);
  } else {
    out.shell_limit = std::move(upward);
  }
  return out;
}

// The water's per-face textures, declared in scene.pov (band_crossings.hpp): an opaque body's
// walls and floor have the body's (two bands where dark meets bright), the free surface two
// bands where dark meets bright and one band across a region's edge, and the other faces the
// water's own, given without an index; none when every face has the water's own.
std::optional<FaceTextures> water_face_textures(const SceneRun& run, const SceneMesh& mesh,
                                                std::span<const TextureCoordinate> uv,
                                                const std::vector<bool>* body) {
  if (run.config.water.shading != WaterShading::toon) return std::nullopt;
  const ToonLimits limits = water_toon_limits(run.layout);
  const bool regions = limits.flow.has_value();
  const std::vector<FaceBands> bands = face_bands(mesh.triangles, uv, limits);
  if (!body &&
      std::all_of(bands.begin(), bands.end(), [](FaceBands b) { return b == FaceBands::three; }))
    return std::nullopt;
  FaceTextures textures;
  textures.names = {kWaterSurfaceTwoBandTexture};
  const auto body_index = static_cast<std::uint8_t>(textures.names.size());
  if (body)
    textures.names.insert(textures.names.end(), {kWaterBodyTexture, kWaterBodyTwoBandTexture});
  const auto one_band_index = static_cast<std::uint8_t>(textures.names.size());
  if (regions)
    textures.names.insert(textures.names.end(), kWaterOneBandTextures.begin(),
                          kWaterOneBandTextures.end());
  textures.index.resize(mesh.triangles.size());
  for (std::size_t f = 0; f < textures.index.size(); ++f) {
    const FaceBands b = bands[f];
    std::uint8_t& index = textures.index[f];
    if (body && (*body)[f])  // the body draws no flow regions
      index = static_cast<std::uint8_t>(body_index + (b == FaceBands::two ? 1 : 0));
    else if (b == FaceBands::three)
      index = FaceTextures::object_texture;
    else if (b == FaceBands::two)
      index = 0;
    else
      index = static_cast<std::uint8_t>(one_band_index + static_cast<int>(b) -
                                        static_cast<int>(FaceBands::only_dark));
  }
  return textures;
}

// The water's outline shell faces written (shell_culling.hpp): `kept` empty for all of them
// (then the shell stays closed), else a mark per face; its faces, and how many are written.
struct WaterShell {
  std::vector<bool> kept;
  std::size_t faces = 0, faces_kept = 0;
};

// `may_cull`: nothing beyond shell_culling.hpp's rule forbids culling this shell. `limit`: the
// faces the shell is limited to anyway.
WaterShell water_shell(const SceneRun& run, const SceneMesh& mesh, std::span<const double> offsets,
                       bool may_cull, const std::vector<bool>* limit) {
  WaterShell shell;
  if (offsets.empty()) return shell;
  shell.faces = mesh.triangles.size();
  // The water's shell is no_reflection whenever the water reflects (scene_writer.cpp).
  if (run.request.cull_shells && may_cull &&
      shell_met_by_camera_rays_only(run.config, /*shell_no_reflection=*/true))
    shell.kept = shell_faces_seen_from_behind(mesh, offsets, run.layout.camera.location,
                                              run.keep_out, limit);
  else if (limit)
    shell.kept = *limit;
  const auto count =
      static_cast<std::size_t>(std::count(shell.kept.begin(), shell.kept.end(), true));
  if (!limit && count == shell.kept.size()) shell.kept.clear();  // every face: stays closed
  shell.faces_kept = shell.kept.empty() ? shell.faces : count;
  return shell;
}

// A frame's spray, foam and bubble particles from every particle cache, in POV-Ray's frame.
struct FrameParticles {
  std::vector<Vec3> spray, foam, bubbles;
  std::vector<Vec3> spray_velocities;  // one per spray particle, or none
};

FrameParticles read_frame_particles(const SceneRun& run, long frame) {
  FrameParticles out;
  for (const Sequence& cache : run.particles) {
    const fs::path& path =
        cache.single_file ? cache.frames.begin()->second : cache.frames.at(frame);
    const ParticleSet set = read_particles(path);
    for (std::size_t i = 0; i < set.positions.size(); ++i) {
      std::vector<Vec3>* kind = set.kinds[i] == ParticleKind::spray    ? &out.spray
                                : set.kinds[i] == ParticleKind::foam   ? &out.foam
                                : set.kinds[i] == ParticleKind::bubble ? &out.bubbles
                                                                       : nullptr;
      if (!kind) continue;
      Vec3 p = set.positions[i];
      if (const std::optional<AffineTransform>& t = run.request.water_transform)
        p = t->linear * p + t->translation;
      if (!(p.cwiseAbs().maxCoeff() < largest_scene_coordinate))  // NaN too
        throw InputError(path.string() + ": particle " + std::to_string(i) +
                         " lies beyond what a POV-Ray scene takes once placed (--scale, "
                         "--translate)");
      kind->push_back(to_povray(p, run.request.up));
      if (kind == &out.spray && !set.velocities.empty()) {
        Vec3 v = set.velocities[i];
        if (const std::optional<AffineTransform>& t = run.request.water_transform)
          v = t->linear * v;
        out.spray_velocities.push_back(to_povray(v, run.request.up));
      }
    }
  }
  // Velocities only when every cache gave them.
  if (out.spray_velocities.size() != out.spray.size()) out.spray_velocities.clear();
  return out;
}

// A frame's particle includes: its spray gathered into droplets in the air over `water` (none:
// a frame without water) and its bubbles under it, each carried on from the last frame; its
// foam as patches on the water.
void write_particles(SceneRun& run, const SceneMesh* water, long frame, long written_frame,
                     FrameResult& result) {
  FrameParticles particles;
  result.read_seconds += seconds_of([&] { particles = read_frame_particles(run, frame); });
  const SceneConfig& c = run.config;
  const ScreenProjection screen =
      screen_projection(run.layout.camera, c.render.width, c.render.height);
  // Droplets and bubbles are outlined as wide as the water in pixels; an outline given in
  // scene units has no size on a shape made on screen, so it takes the default width in pixels.
  const double line_pixels = !c.outline.enabled ? 0.0
                             : c.outline.units == WidthUnits::pixels
                                 ? c.outline.width.value_or(kDefaultOutlinePixels)
                                 : kDefaultOutlinePixels;
  if (run.layout.spray) {
    DropletOptions options;
    options.size_pixels = c.particles.droplet_size;
    options.max_droplets = static_cast<std::size_t>(c.particles.max_droplets);
    std::vector<Droplet> droplets =
        run.droplets.update(spray_droplets(particles.spray, screen, options, water,
                                           run.droplets.predicted(), particles.spray_velocities),
                            screen, options);
    result.particles = particles.spray.size();
    result.droplets = droplets.size();
    result.write_seconds += run.write(spray_include_name(written_frame),
                                      spray_include(droplets, screen, run.light, line_pixels));
  }
  if (run.layout.bubbles) {
    DropletOptions options;
    options.size_pixels = c.particles.bubble_size;
    options.max_droplets = static_cast<std::size_t>(c.particles.max_bubbles);
    options.under_water = true;
    // Without water nothing is under it.
    std::vector<Droplet> bubbles =
        water ? run.bubbles.update(spray_droplets(particles.bubbles, screen, options, water,
                                                  run.bubbles.predicted()),
                                   screen, options)
              : std::vector<Droplet>{};
    result.bubble_particles = particles.bubbles.size();
    result.bubbles = bubbles.size();
    result.write_seconds += run.write(bubbles_include_name(written_frame),
                                      bubble_include(bubbles, screen, line_pixels));
  }
  if (run.layout.foam) {
    const FoamOptions options{c.particles.foam_reach, c.particles.foam_density};
    // Without water there is no surface to paint.
    const std::vector<FoamComponent> components =
        water ? foam_components(particles.foam, *water, screen, options)
              : std::vector<FoamComponent>{};
    result.foam_particles = particles.foam.size();
    result.foam_components = components.size();
    result.write_seconds +=
        run.write(foam_include_name(written_frame), foam_include(components, options.density));
  }
}

// A frame with no liquid: the scene still needs its include, with nothing in it.
void write_empty_frame(SceneRun& run, long frame, long written_frame, const std::string& why,
                       FrameResult& result) {
  if (run.water.frames.size() == 1) throw InputError(why);
  result.empty = why;
  result.objects += write_animated_objects(run, frame, written_frame);
  result.write_seconds += run.write(water_include_name(written_frame),
                                    empty_water_include() + object_waters(run, nullptr));
  if (run.layout.spray || run.layout.foam || run.layout.bubbles)
    write_particles(run, nullptr, frame, written_frame, result);
}

// A water frame's include: its text (the render mesh with its textures, outline shell and flow
// strokes, then each object's water) and its outline shell.
struct WaterInclude {
  std::string text;
  WaterShell shell;
};

// A closed volume's surface and its coordinates `uv` are first cut where its body meets its free
// surface (water_body_faces).
WaterInclude water_include(SceneRun& run, PreparedSurface& s, std::vector<TextureCoordinate>& uv) {
  const WaterBodyFaces body = water_body_faces(run, s, uv);
  const SceneConfig& config = run.config;
  const std::vector<double> offsets =
      config.outline.enabled
          ? shell_offsets(config.outline, s.mesh, run.layout.camera, config.render.width)
          : std::vector<double>{};
  if (body.body) run.layout.closed_water = true;
  const std::optional<FaceTextures> textures =
      water_face_textures(run, s.mesh, uv, body.body ? &*body.body : nullptr);
  // Flow lines are strokes on the water, reaching up towards its shell.
  WaterInclude include;
  include.shell = water_shell(run, s.mesh, offsets, s.flow_lines.empty(),
                              body.shell_limit ? &*body.shell_limit : nullptr);
  const std::vector<bool>& kept = include.shell.kept;
  include.text = mesh_include(s, "Water", uv, offsets, textures ? &*textures : nullptr,
                              kept.empty() ? nullptr : &kept) +
                 object_waters(run, &s.mesh);
  return include;
}

// The water include of one frame that has water, with its counts and times in `result`.
void write_water_frame(SceneRun& run, PreparedSurface& s, long frame, long written_frame,
                       FrameResult& result) {
  add_to_layout(run, s);
  s.view_range = run.view_range;
  result.vertices = s.mesh.positions.size();
  result.faces = s.mesh.triangles.size();
  result.degenerate_faces = s.mesh.degenerate_faces;
  result.replaced_normals = s.mesh.replaced_normals;
  result.ridge_vertices = s.ridge_vertices;
  result.valley_vertices = s.valley_vertices;
  result.objects += write_animated_objects(run, frame, written_frame);

  std::vector<TextureCoordinate> uv = water_coordinates(s, run.light, run.layout);
  // The particles meet the water as analysed (foam_patches.hpp), before it is simplified.
  if (run.layout.spray || run.layout.foam || run.layout.bubbles)
    write_particles(run, &s.mesh, frame, written_frame, result);
  result.simplify_seconds = seconds_of([&] { simplify_water(s, uv, run.layout, run.plan.flow); });
  result.faces_kept = s.mesh.triangles.size();

  WaterInclude include;
  result.write_seconds = seconds_of([&] { include = water_include(run, s, uv); });
  result.shell_faces = include.shell.faces;
  result.shell_faces_kept = include.shell.faces_kept;
  result.write_seconds += run.write(water_include_name(written_frame), include.text);
}

// A water frame as the frame loop takes it: why it has no water ("" when it has), its maps'
// inputs (with maps) and its prepared surface.
struct LoopFrame {
  std::string empty;
  std::optional<MapInputs> maps;
  PreparedSurface surface;
};

// Frame i from the survey's cache; the survey's copies of its animated objects go to their
// includes (SceneRun::object_mesh).
LoopFrame take_cached_frame(SceneRun& run, FrameCache& cache, std::size_t i, std::string& bytes) {
  cache.take(i, bytes);
  RecordReader record(bytes);
  LoopFrame in;
  in.empty = record.string();
  if (in.empty.empty() && run.map_view) in.maps = unpack_map_inputs(record);
  if (in.empty.empty()) in.surface = unpack_surface(record);
  for (std::size_t o = 0; run.plan.survey_reads_objects() && o < run.objects.size(); ++o)
    if (run.objects[o].placement.animated) mesh_fields(record, run.object_mesh[o].emplace());
  return in;
}

// One frame's maps and includes; `result` holds its reads, and is returned complete.
FrameResult write_frame(SceneRun& run, LoopFrame in, long frame, const fs::path& path,
                        FrameResult result) {
  result.frame = frame;
  const long written_frame = run.layout.animation ? frame : 0;
  if (!in.empty.empty()) {
    write_empty_frame(run, frame, written_frame, in.empty, result);
    return result;
  }
  PreparedSurface& s = in.surface;
  result.analysis_seconds += s.analysis_seconds;
  if (in.maps) {
    result.maps_seconds = seconds_of([&] {
      write_maps(run.request.maps_dir, frame_stem(path),
                 rasterize_top_down(in.maps->surface, in.maps->curvature, in.maps->label,
                                    in.maps->free_surface, *run.map_view),
                 run.map_ranges);
    });
    result.maps = true;
  }
  check_scene_extent(s.mesh, path);
  // POV-Ray rejects a mesh2 without faces: a frame of zero-area faces only has no water.
  if (s.mesh.triangles.empty())
    write_empty_frame(run, frame, written_frame,
                      path.string() + ": all " + std::to_string(s.mesh.degenerate_faces) +
                          " faces are degenerate (zero area)",
                      result);
  else
    write_water_frame(run, s, frame, written_frame, result);
  return result;
}

// The frame loop's results, in frame order, and the water files it read itself.
struct FrameLoop {
  std::vector<FrameResult> frames;
  std::size_t water_reads = 0;
};

// The frame loop: each water frame's include written, and its maps, from its one read and
// analysis: taken from the survey's `cache` (with the survey's `reads` of each frame), or,
// without one, read and analysed here.
FrameLoop write_frames(SceneRun& run, FrameCache* cache, std::vector<FrameResult> reads,
                       const ProgressFn& progress, const std::atomic<bool>* stop) {
  FrameLoop loop;
  std::optional<FrameSource> source;
  if (!cache) source.emplace(run.plan.frames);
  std::string bytes;  // one buffer for every frame's record
  for (const auto& [frame, path] : run.water.frames) {
    throw_if_stopped(run, stop);
    const std::size_t i = loop.frames.size();
    if (cache) {
      LoopFrame in = take_cached_frame(run, *cache, i, bytes);
      loop.frames.push_back(write_frame(run, std::move(in), frame, path, std::move(reads[i])));
    } else {
      SourceFrame f = source->read(path);
      LoopFrame in;
      in.empty = f.empty;
      if (f.has_water()) in.surface = run.prepare(f);
      loop.frames.push_back(write_frame(run, std::move(in), frame, path, frame_reads(f)));
    }
    if (progress) progress(PovgenPass::frames, i + 1, run.water.frames.size());
  }
  if (source) loop.water_reads = source->reads();
  return loop;
}

}  // namespace

PovgenReport generate_scene(const SceneConfig& config, const PovgenRequest& request,
                            const ProgressFn& progress, const std::atomic<bool>* stop) {
  const Sequence water = select_frames(config, request);
  SceneRun run(config, request, water);
  run.objects = find_objects(config, water);
  run.particles = find_particles(request, water);
  run.plan = plan_water(config, request, water.frames.size());
  run.layout.config = &config;
  run.layout.up = request.up;
  run.layout.animation = water.frames.size() > 1;
  run.layout.first_frame = run.layout.animation ? water.frames.begin()->first : 0;
  run.layout.last_frame = run.layout.animation ? water.frames.rbegin()->first : 0;
  run.layout.spray =
      !run.particles.empty() && config.particles.spray && config.particles.max_droplets > 0;
  run.layout.foam =
      !run.particles.empty() && config.particles.foam && config.water.shading == WaterShading::toon;
  // Bubbles are seen through the water only.
  run.layout.bubbles = !run.particles.empty() && config.particles.bubbles &&
                       config.particles.max_bubbles > 0 &&
                       config.water.shading == WaterShading::toon && config.water.transmit > 0;
  run.light = light_geometry(config.light, request.up);
  RunResult totals;
  totals.first_frame = run.layout.first_frame;
  totals.last_frame = run.layout.last_frame;
  run.object_box.resize(run.objects.size());
  run.keep_out.resize(run.objects.size());
  run.submerged.assign(run.objects.size(), false);
  run.contact_depth.assign(run.objects.size(), 0.0);
  run.object_mesh.resize(run.objects.size());

  if (!request.maps_dir.empty() && fs::is_directory(request.maps_dir))
    remove_stale_temporaries(request.maps_dir);
  SceneDirectory scene(request.out_dir, request.force);
  // The maps directories this run makes go again if it fails (they are empty then).
  const NewDirectories new_maps_directories(request.maps_dir);
  PovgenReport report;
  try {
    run.out_dir = scene.staging();
    // With maps, every file of the scene and the maps is renamed into place at the end, together
    // (OutputBatch): both outputs are replaced, or neither.
    std::optional<OutputBatch> batch;
    if (run.plan.maps) batch.emplace();

    // The survey's frames wait in the staging directory's cache file, removed before the commit.
    std::optional<FrameCache> cache;
    SequenceSurvey survey;
    if (run.plan.shares()) {
      cache.emplace(run.out_dir / ".frame_cache.bin", request.frame_cache_bytes);
      survey = survey_sequence(run, *cache, progress, stop);
    }
    run.layout.camera = frame_camera(config, request.up, survey.box_min, survey.box_max);
    if (!survey.normal_noise.empty()) {
      auto middle =
          survey.normal_noise.begin() + static_cast<std::ptrdiff_t>(survey.normal_noise.size() / 2);
      std::nth_element(survey.normal_noise.begin(), middle, survey.normal_noise.end());
      run.layout.normal_noise = *middle;
    }
    if (run.plan.shading != WaterShading::toon)
      run.view_range = view_range(survey.view, run.plan.shading);
    if (survey.maps) {
      const MapOptions map_options;
      run.map_view = survey.maps->view(map_options);
      run.map_ranges = survey.maps->ranges(map_options.percentile);
      totals.map_ranges = run.map_ranges;
    }

    // Static objects first.
    totals.static_objects = survey.static_objects;
    for (std::size_t i = 0; i < run.objects.size(); ++i)
      if (!run.objects[i].placement.animated)
        totals.static_objects +=
            write_object(run, i, run.objects[i].sequence.frames.begin()->second, 0);
    FrameLoop loop =
        write_frames(run, cache ? &*cache : nullptr, std::move(survey.frames), progress, stop);
    totals.water_reads = survey.water_reads + loop.water_reads;
    // A sequence without water anywhere has nothing to show or frame, as a single empty file.
    if (!loop.frames.empty() && std::all_of(loop.frames.begin(), loop.frames.end(),
                                            [](const FrameResult& f) { return !f.empty.empty(); }))
      throw InputError(request.water_pattern + ": no frame of the sequence holds any water (" +
                       loop.frames.front().empty + ")");
    if (cache) {
      totals.cached_frames = cache->size();
      totals.spilled_frames = cache->spilled();
    }
    cache.reset();

    for (std::size_t i = 0; i < run.objects.size(); ++i) {
      run.objects[i].placement.submerged = run.submerged[i];
      run.layout.objects.push_back(run.objects[i].placement);
    }
    totals.write_seconds += run.write("toon.inc", scene_toon_inc(run.layout));
    totals.write_seconds += run.write("scene.ini", scene_ini(run.layout));
    totals.write_seconds += run.write("scene.pov", scene_pov(run.layout));
    if (batch) batch->commit();
    scene.commit();
    report = summarise(std::move(loop.frames), totals);
  } catch (...) {
    new_maps_directories.remove_empty();
    throw;
  }
  return report;
}

}  // namespace toonwater
