// toonwater render DIR [--jobs N] [--frames A-B] [--video mp4,gif]
//                      [farm options: render_farm_command.cpp]
#include "cli/commands.hpp"
#include "cli/render_farm.hpp"

#include "cli/progress.hpp"
#include "cli/stop_signals.hpp"
#include "cli/validators.hpp"
#include "analyzer/mesh_reader.hpp"  // InputError
#include "render/render.hpp"
#include "render/video.hpp"
#include "scene/config.hpp"  // parse_frame_range

#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater::cli {
namespace {

struct RenderArgs {
  std::string dir;
  int jobs = 0;
  std::string frames;
  std::vector<VideoFormat> videos;
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

// The videos asked for, checked before any frame is rendered: the scene is an animation, ffmpeg
// is there, and this run waits for every frame.
VideoRequest checked_video_request(const RenderArgs& args, const FarmArgs& farm) {
  VideoRequest video;
  video.scene_dir = args.dir;
  video.formats = args.videos;
  if (video.formats.empty()) return video;
  if (farm.status || farm.no_wait)
    throw InputError(
        "--video is made once every frame is rendered: not with --status or --no-wait");
  if (!args.frames.empty()) video.frames = parse_frame_range(args.frames, "--frames");
  check_video_request(video);
  return video;
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
  cmd->add_option("--video", args->videos,
                  "Once every frame is rendered, make DIR/video.mp4 (H.264) or DIR/video.gif (a "
                  "small preview) with ffmpeg; repeatable or a list: mp4,gif")
      ->delimiter(',')
      ->allow_extra_args(false)  // `--video mp4 DIR`: DIR is the directory, not a format
      ->transform(one_of<VideoFormat>({{"mp4", VideoFormat::mp4}, {"gif", VideoFormat::gif}}));
  auto farm = std::make_shared<FarmArgs>();
  add_render_farm_options(cmd, farm);
  cmd->callback([args, farm] {
    VideoRequest video = checked_video_request(*args, *farm);
    if (!run_render_on_farm(args->dir, args->frames, *farm)) run_render(*args, farm->force);
    if (video.formats.empty()) return;
    // A stop signal stops ffmpeg and removes its partial output; the frames stay.
    video.stop = stop_on_signals();
    for (const auto& path : make_videos(video)) std::printf("%s\n", path.c_str());
  });
}

}  // namespace toonwater::cli
