// toonwater render DIR [--jobs N] [--frames A-B] [farm options: render_farm_command.cpp]
#include "cli/commands.hpp"
#include "cli/render_farm.hpp"

#include "cli/progress.hpp"
#include "cli/stop_signals.hpp"
#include "cli/validators.hpp"
#include "render/render.hpp"
#include "scene/config.hpp"  // parse_frame_range

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>

namespace toonwater::cli {
namespace {

struct RenderArgs {
  std::string dir;
  int jobs = 0;
  std::string frames;
};

// `force`: the farm options' --force (local and farm renders skip frames with an image alike).
void run_render(const RenderArgs& args, bool force) {
  RenderRequest request;
  request.scene_dir = args.dir;
  request.skip_rendered = !force;
  request.jobs = args.jobs > 0 ? args.jobs : default_render_processes();
  if (!args.frames.empty()) request.frames = parse_frame_range(args.frames, "--frames");
  // The POV-Ray executable: TOONWATER_POVRAY when set (a path or a name on PATH), else povray.
  if (const char* povray = std::getenv("TOONWATER_POVRAY"); povray && *povray)
    request.povray = povray;
  // A stop signal stops the running povray processes and removes their partial output; frames
  // already rendered stay.
  request.stop = stop_on_signals();
  FrameProgress shown("render");
  auto progress = [&](std::size_t done, std::size_t total, double elapsed) {
    shown.update(done, total, elapsed);
  };
  RenderReport r;
  try {
    r = render_frames(request, progress);
  } catch (...) {
    shown.finish_line();
    throw;
  }
  for (const auto& f : r.failures)
    std::fprintf(stderr, "render: frame %ld failed: %s\n", f.frame, f.message.c_str());
  std::fprintf(
      stderr, "render: %zu frame(s) rendered, %zu skipped (already rendered), %zu failed, %.2f s\n",
      r.rendered, r.skipped, r.failures.size(), r.seconds);
  if (!r.failures.empty())
    throw PovrayError(args.dir + ": " + std::to_string(r.failures.size()) +
                      " frame(s) failed to render");
}

}  // namespace

void add_render_command(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a povgen scene directory with POV-Ray");
  cmd->add_option("dir", args->dir, "Scene directory written by toonwater povgen")
      ->required()
      ->check(NonEmptyPath);
  cmd->add_option(
         "--jobs", args->jobs,
         "POV-Ray processes at the same time, each over a range of frames (default: four a core)")
      ->check(PositiveNumber);
  cmd->add_option("--frames", args->frames, "Frame range A-B (default: all)");
  auto farm = std::make_shared<FarmArgs>();
  add_render_farm_options(cmd, farm);
  cmd->callback([args, farm] {
    if (run_render_on_farm(args->dir, args->frames, *farm)) return;
    run_render(*args, farm->force);
  });
}

}  // namespace toonwater::cli
