// toonwater analyze MESH [--csv FILE] [--ply FILE] [options]
#include "cli/commands.hpp"
#include "cli/analysis_options.hpp"
#include "cli/progress.hpp"
#include "cli/level_set_options.hpp"
#include "cli/transform_options.hpp"
#include "cli/validators.hpp"

#include "analyzer/affine_transform.hpp"
#include "analyzer/analysis.hpp"
#include "analyzer/analysis_settings.hpp"
#include "common/atomic_file.hpp"
#include "analyzer/curvature_export.hpp"
#include "analyzer/maps/map_writer.hpp"
#include "analyzer/mesh_reader.hpp"
#include "analyzer/stopwatch.hpp"
#include "images/image_codec.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace toonwater::cli {
namespace {

struct AnalyzeArgs {
  std::string mesh;
  TransformArgs transform;
  LevelSetOptions level_set;
  std::string csv;
  std::string ply;
  std::string maps;              // directory for the curvature maps
  std::optional<int> maps_size;  // pixels along the longer side
  std::vector<double> maps_box;  // u_min, v_min, u_max, v_max
  Axis up = Axis::y;
  AnalysisSettings analysis;
};

void print_summary(const std::string& mesh_path, const Analysis& a, double read_seconds,
                   double write_seconds) {
  const auto& t = a.topology;
  const auto& f = a.flow;
  std::fprintf(stderr,
               "%s: %zu vertices (%zu welded), %zu faces\n"
               "  boundary %zu, non-manifold %zu, isolated %zu vertices; degenerate faces "
               "%zu, caps %zu, mollified faces %zu (intrinsic flips %zu), flipped faces %zu;\n"
               "  curvature extrapolated at %zu, undefined at %zu\n"
               "  flow (%s): T = %.6g (scene length %.6g, noise floor %.6g, %zu tank walls), "
               "rest height %.6g, free surface %zu "
               "vertices (%zu patches dropped), %zu regions (%zu specks faded below %.6g), "
               "ridge %zu, valley %zu\n"
               "  time: read %.3f s, weld %.3f s, topology %.3f s, curvature %.3f s, "
               "flow %.3f s, write %.3f s\n",
               printable(mesh_path).c_str(), a.input_vertices, a.merged_vertices,
               a.surface.triangles.size(), t.boundary_vertices, t.nonmanifold_vertices,
               t.isolated_vertices, a.curvature.degenerate_faces, a.curvature.cap_faces,
               a.curvature.mollified_faces, a.curvature.intrinsic_flips, a.flipped_faces,
               a.curvature.extrapolated_vertices, a.curvature.undefined_vertices,
               f.criterion == FlowCriterion::mean ? "mean" : "paper", f.threshold, f.scale_length,
               f.sequence_noise_floor, f.walls, f.rest_height, f.free_surface_vertices,
               f.free_surface_patches_dropped, f.regions, f.specks_faded, f.min_region_area,
               f.ridge_vertices, f.valley_vertices, read_seconds, a.times.weld, a.times.topology,
               a.times.curvature, a.times.flow, write_seconds);
}

// Two names of one file: the same existing file (hard links included), or the same file to be
// written once links are followed (output_target), whether it exists yet or not.
bool same_file(const std::string& a, const std::string& b) {
  if (a == "-" || b == "-") return a == b;
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec) && !ec) return true;
  return output_target(a) == output_target(b);
}

// Refuses, before anything is read or written, an output that is the input or another output.
void check_outputs(const AnalyzeArgs& args) {
  const std::vector<std::pair<const char*, std::string>> outputs{{"--csv", args.csv},
                                                                 {"--ply", args.ply}};
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    if (path.empty()) continue;
    if (same_file(path, args.mesh))
      throw InputError(path + ": " + option + " names the input mesh; refusing to overwrite it");
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
      if (!outputs[j].second.empty() && same_file(path, outputs[j].second))
        throw InputError(path + ": given to both " + option + " and " + outputs[j].first);
  }
  if (!args.maps.empty() && same_file(args.maps, args.mesh))
    throw InputError(args.maps + ": --maps names the input mesh");
  if (args.maps.empty()) return;
  const MapFiles maps = map_files(args.maps, frame_stem(args.mesh));
  for (const auto& [option, path] : outputs)
    for (const std::filesystem::path& map :
         {maps.exr, maps.gaussian_png, maps.mean_png, maps.label_png})
      if (!path.empty() && same_file(path, map.string()))
        throw InputError(path + ": given to both " + option + " and --maps (" +
                         map.filename().string() + ")");
}

void run_analyze(const AnalyzeArgs& args) {
  check_outputs(args);
  if (!args.maps.empty()) image_codec();  // a missing image module fails before any work
  // Temporaries that killed runs left where this one writes.
  for (const std::string& path : {args.csv, args.ply})
    if (!path.empty() && path != "-")
      remove_stale_temporaries(std::filesystem::path(path).parent_path());
  if (!args.maps.empty() && std::filesystem::is_directory(args.maps))
    remove_stale_temporaries(args.maps);
  const std::optional<AffineTransform> transform = transform_from(args.transform);
  check_level_set_options(args.level_set, args.mesh);
  auto start = Clock::now();
  InputMesh input = read_mesh(args.mesh, args.level_set);
  if (transform) apply_transform(*transform, input.mesh, args.mesh);
  const double read_seconds = seconds_since(start);

  // The PLY repeats the input's faces; nothing else needs the input once it is analysed.
  const std::vector<Triangle> input_triangles =
      args.ply.empty() ? std::vector<Triangle>{} : input.mesh.triangles;
  AnalyzeOptions options = analyze_options(args.analysis, args.up);
  options.flow.shading_normals = false;  // no output of analyze holds them
  const Analysis analysis = analyze_mesh(std::move(input.mesh), options);

  start = Clock::now();
  // The maps directories this run makes are removed again if it fails (they are empty then).
  const NewDirectories new_maps_directories(args.maps);
  std::optional<MapRanges> map_ranges;
  try {
    // Every output, or none: the renames wait until all of them are complete.
    OutputBatch outputs;
    if (!args.csv.empty()) write_curvature_csv(args.csv, analysis);
    if (!args.ply.empty()) write_curvature_ply(args.ply, input_triangles, analysis);
    if (!args.maps.empty()) {
      MapOptions map_options;
      map_options.size = args.maps_size;
      if (args.maps_box.size() == 4)
        map_options.box =
            MapBox{args.maps_box[0], args.maps_box[1], args.maps_box[2], args.maps_box[3]};
      map_ranges =
          write_frame_maps(args.maps, frame_stem(args.mesh), analysis, args.up, map_options);
    }
    outputs.commit();
  } catch (...) {
    new_maps_directories.remove_empty();
    throw;
  }
  print_summary(args.mesh, analysis, read_seconds, seconds_since(start));
  if (map_ranges)
    std::fprintf(stderr, "  maps in %s: colour ranges K \u00b1%.6g, H \u00b1%.6g\n",
                 printable(args.maps).c_str(), map_ranges->gaussian, map_ranges->mean);
}

}  // namespace

void add_analyze_command(CLI::App& app) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "analyze", "Compute per-vertex curvature and water-flow regions of a surface mesh");
  cmd->add_option("mesh", args->mesh,
                  "Surface mesh: OBJ, OFF, PLY, STL, legacy VTK, Mantaflow .bobj.gz, FLIP Fluids "
                  ".bobj or an OpenVDB level set (.vdb)")
      ->required()
      ->check(NonEmptyPath);
  add_transform_options(*cmd, args->transform);
  add_level_set_options(*cmd, args->level_set);
  cmd->add_option("--csv", args->csv, "Write x,y,z,gaussian,mean,k1,k2,area,label,flow per vertex")
      ->check(NonEmptyPath);
  cmd->add_option("--ply", args->ply, "Write a binary PLY with the curvature as vertex properties")
      ->check(NonEmptyPath);
  cmd->add_option("--maps", args->maps,
                  "Write top-down curvature maps (EXR + PNG previews) into this directory")
      ->check(NonEmptyPath);
  cmd->add_option("--maps-size", args->maps_size,
                  "Map pixels along the longer side (default: 2 per median edge length)")
      ->check(CLI::Range(1, 4096));
  cmd->add_option("--maps-box", args->maps_box,
                  "Map extent u_min,v_min,u_max,v_max seen from above (default: the surface's)")
      ->expected(4)
      ->delimiter(',')
      ->check(FiniteNumber);
  cmd->add_option("--up", args->up, "Up axis of the input (Blender writes z)")
      ->transform(one_of<Axis>({{"x", Axis::x}, {"y", Axis::y}, {"z", Axis::z}}))
      ->default_str("y");
  add_analysis_options(*cmd, args->analysis);
  cmd->callback([args] { run_analyze(*args); });
}

}  // namespace toonwater::cli
