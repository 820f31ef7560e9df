// toonwater simulate wake|drop|reflection|refraction --frames N --out DIR [--resolution R]
#include "cli/commands.hpp"
#include "cli/validators.hpp"
#include "cli/progress.hpp"

#include "common/atomic_file.hpp"
#include "analyzer/obj_writer.hpp"
#include "sim/scenarios.hpp"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

namespace toonwater::cli {
namespace {

struct SimulateArgs {
  std::string scenario;
  int frames = 24;
  int resolution = 0;
  std::string out;
};

void run_simulate(const SimulateArgs& args) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(args.out, ec);
  if (ec) throw OutputError(args.out + ": cannot create directory: " + ec.message());
  remove_stale_temporaries(args.out);  // of runs that were killed

  const auto start = std::chrono::steady_clock::now();
  std::size_t files = 0, water_vertices = 0;
  auto sink = [&](const std::string& name, const TriangleMesh& mesh) {
    write_obj(fs::path(args.out) / name, mesh,
              "toonwater simulate " + args.scenario + ": " + name + " (y up)");
    ++files;
    if (name.starts_with("water_")) water_vertices = mesh.positions.size();
  };
  FrameProgress shown("simulate");
  auto progress = [&](int done, int total) {
    shown.update(static_cast<std::size_t>(done), static_cast<std::size_t>(total),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  };
  // The frames are put in place together once every one is written: a run that fails or is
  // interrupted half-way leaves the earlier frames, not a mix of two simulations.
  try {
    OutputBatch batch;
    sim::simulate({args.scenario, args.frames, args.resolution}, sink, progress);
    batch.commit();
  } catch (...) {
    shown.finish_line();
    throw;
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fprintf(stderr,
               "simulate: %s, %d frame(s), %zu water vertices a frame -> %s (%zu OBJ files, "
               "y up), %.2f s\n",
               args.scenario.c_str(), args.frames, water_vertices, printable(args.out).c_str(),
               files, seconds);
}

}  // namespace

void add_simulate_command(CLI::App& app) {
  auto args = std::make_shared<SimulateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "simulate", "Simulate an example scene (height-field waves) and write OBJ frames");
  cmd->add_option("scenario", args->scenario, "wake, drop, reflection or refraction")
      ->required()
      ->check(CLI::IsMember(sim::scenario_names()));
  cmd->add_option("--frames", args->frames, "Number of frames")
      ->check(CLI::Range(1, 100000))
      ->default_str("24");
  cmd->add_option("--resolution", args->resolution,
                  "Grid cells along the longer side (refraction: segments around the body)")
      ->check(CLI::Range(8, 2048));
  cmd->add_option("--out", args->out, "Output directory")->required()->check(NonEmptyPath);
  cmd->callback([args] { run_simulate(*args); });
}

}  // namespace toonwater::cli
