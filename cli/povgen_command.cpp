// toonwater povgen --water PATTERN [--object PATTERN]... [--particles PATTERN]...
//                  [--config scene.toml]
//                  [--set key=value]... [--up x|y|z] --out DIR
#include "cli/commands.hpp"
#include "cli/progress.hpp"
#include "cli/level_set_options.hpp"
#include "cli/transform_options.hpp"
#include "cli/stop_signals.hpp"
#include "cli/validators.hpp"

#include "common/atomic_file.hpp"
#include "images/image_codec.hpp"
#include "pipeline/generate_scene.hpp"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::cli {
namespace {

struct PovgenArgs {
  std::string water;
  std::vector<std::string> objects;
  std::vector<std::string> particles;
  std::string config;
  std::vector<std::string> overrides;
  std::string out;
  bool force = false;
  Axis up = Axis::y;
  std::string maps;  // curvature maps of the water frames, one shared colour range
  TransformArgs water_transform;
  LevelSetOptions water_level_set;
};

void run_povgen(const PovgenArgs& args) {
  if (!args.maps.empty()) image_codec();  // a missing image module fails before any work
  ConfigSources sources;
  if (!args.config.empty()) sources.file = args.config;
  sources.object_patterns = args.objects;
  sources.overrides = args.overrides;
  const SceneConfig config = load_config(sources);

  PovgenRequest request;
  request.water_pattern = args.water;
  request.water_transform = transform_from(args.water_transform);
  check_level_set_options(args.water_level_set, args.water);
  request.water_level_set = args.water_level_set;
  request.particle_patterns = args.particles;
  request.base_dir = std::filesystem::current_path();
  request.up = args.up;
  request.out_dir = args.out;
  request.force = args.force;

  request.maps_dir = args.maps;

  // A stop signal stops between frames; the scene directory is then left as it was.
  const std::atomic<bool>* stop = stop_on_signals();
  // Each pass's progress is timed from its own start, so the time left is the pass's.
  FrameProgress shown("povgen");
  auto pass_start = std::chrono::steady_clock::now(), last_update = pass_start;
  std::optional<PovgenPass> shown_pass;
  auto progress = [&](PovgenPass pass, std::size_t done, std::size_t total) {
    const auto now = std::chrono::steady_clock::now();
    if (shown_pass && *shown_pass != pass) pass_start = last_update;  // as the last pass ended
    shown_pass = pass;
    last_update = now;
    shown.update(done, total, std::chrono::duration<double>(now - pass_start).count(),
                 pass == PovgenPass::survey ? "survey" : nullptr);
  };
  PovgenReport r;
  try {
    r = generate_scene(config, request, progress, stop);
  } catch (...) {
    shown.finish_line();
    throw;
  }
  // From here on a signal ends the run at once (removing any temporary file), as before povgen.
  remove_temporaries_on_signals();
  // A signal that came after the last frame's check found the scene complete and in place.
  if (stop->load())
    std::fprintf(stderr,
                 "povgen: the stop signal came once the scene was complete; it is in place\n");
  for (const std::string& empty : r.empty_frames)
    std::fprintf(stderr, "povgen: warning: %s; that frame shows no water\n",
                 printable(empty).c_str());
  std::fprintf(stderr,
               "povgen: %zu frame(s) -> %s (%zu water vertices, %zu degenerate faces left out, "
               "%zu normals replaced, ridge %zu, valley %zu%s)\n"
               "  render mesh: %zu of %zu water faces kept (water.simplify)\n"
               "  time: read %.3f s, analysis %.3f s, simplification %.3f s, scene writing %.3f s\n"
               "  render: cd %s && povray scene.ini   (or: toonwater render %s)\n",
               r.frames, printable(args.out).c_str(), r.vertices, r.degenerate_faces,
               r.replaced_normals, r.ridge_vertices, r.valley_vertices,
               r.empty_frames.empty() ? "" : "; frames without water listed above", r.faces_kept,
               r.faces, r.read_seconds, r.analysis_seconds, r.simplify_seconds, r.write_seconds,
               printable_shell_word(args.out).c_str(), printable_shell_word(args.out).c_str());
  if (!args.particles.empty())
    std::fprintf(stderr,
                 "  spray: %zu particles -> %zu droplets; foam: %zu particles -> %zu patch "
                 "components; bubbles: %zu particles -> %zu bubbles; over the frames "
                 "(particles.*)\n",
                 r.particles, r.droplets, r.foam_particles, r.foam_components, r.bubble_particles,
                 r.bubbles);
  if (!args.maps.empty()) {
    std::fprintf(
        stderr, "  maps: %zu frame(s) -> %s, shared colour ranges K \u00b1%.6g, H \u00b1%.6g\n",
        r.map_frames, printable(args.maps).c_str(), r.map_ranges.gaussian, r.map_ranges.mean);
  }
}

}  // namespace

void add_povgen_command(CLI::App& app) {
  auto args = std::make_shared<PovgenArgs>();
  CLI::App* cmd = app.add_subcommand(
      "povgen", "Write POV-Ray scenes (Cartoon Water Shader) for a mesh or a frame sequence");
  cmd->add_option("--water", args->water,
                  "Water mesh: a file, a numbered sequence (sim/water_####.obj) or a glob")
      ->required()
      ->check(NonEmptyPath);
  cmd->add_option("--object", args->objects,
                  "Object mesh (static file or per-frame sequence); repeatable")
      ->check(NonEmptyPath);
  cmd->add_option("--particles", args->particles,
                  "Secondary particle cache (.vdb point grid, .wwp; file or per-frame sequence), "
                  "placed like the water (--scale, --translate); repeatable")
      ->check(NonEmptyPath);
  cmd->add_option("--config", args->config, "Scene configuration (TOML)")->check(CLI::ExistingFile);
  cmd->add_option("--set", args->overrides, "Override a configuration key: section.key=value");
  cmd->add_option("--out", args->out,
                  "Scene directory: new, empty or an earlier scene, which is replaced whole")
      ->required()
      ->check(NonEmptyPath);
  cmd->add_flag("--force", args->force,
                "Write into a non-empty directory that is not a toonwater scene (only the "
                "scene's own files there are replaced)");
  cmd->add_option("--maps", args->maps,
                  "Also write top-down curvature maps of the water frames into this directory, "
                  "with one colour range shared by all frames")
      ->check(NonEmptyPath);
  add_transform_options(*cmd, args->water_transform);  // applies to the water meshes
  add_level_set_options(*cmd, args->water_level_set);  // so do these
  cmd->add_option("--up", args->up, "Up axis of the input (Blender writes z)")
      ->transform(one_of<Axis>({{"x", Axis::x}, {"y", Axis::y}, {"z", Axis::z}}))
      ->default_str("y");
  cmd->callback([args] { run_povgen(*args); });
}

}  // namespace toonwater::cli
