// toonwater render DIR --on slurm|parallel ... and --status: the render farm options of `render`;
// toonwater render-task DIR --frames A-B: what each farm task runs (hidden).
#include "cli/progress.hpp"
#include "cli/render_farm.hpp"
#include "cli/stop_signals.hpp"
#include "cli/validators.hpp"

#include "analyzer/mesh_reader.hpp"
#include "render/farm_parallel.hpp"
#include "render/farm_slurm.hpp"
#include "scene/config.hpp"  // parse_frame_range

#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace toonwater::cli {
namespace {

// The tasks run this very executable, by its absolute path (the same on every host of a farm).
std::string own_executable() {
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot find the toonwater executable: " + ec.message());
  return exe.string();
}

void report_failures(const std::vector<FrameFailure>& failures) {
  for (const auto& f : failures)
    std::fprintf(stderr, "render: frame %ld failed: %s\n", f.frame, f.message.c_str());
}

void print_progress(const std::string& line) { std::fprintf(stderr, "render: %s\n", line.c_str()); }

}  // namespace

void add_render_farm_options(CLI::App* cmd, const std::shared_ptr<FarmArgs>& farm) {
  cmd->add_option("--on", farm->on,
                  "Render on a farm: slurm (a job array) or parallel (GNU parallel)")
      ->check(CLI::IsMember({"slurm", "parallel"}));
  cmd->add_option("--partition", farm->partition, "Slurm partition (default: the cluster's)");
  cmd->add_option("--frames-per-task", farm->frames_per_task, "Frames a farm task renders (10)")
      ->check(CLI::Range(1L, 10'000'000L));  // CLI::PositiveNumber's error prints 309 digits
  cmd->add_option("--sbatch-arg", farm->sbatch_args, "An argument passed to sbatch (repeatable)")
      ->allow_extra_args(false);
  cmd->add_flag("--no-wait", farm->no_wait, "Slurm: print the job id and return at once");
  cmd->add_flag("--status", farm->status, "Report on the farm job last submitted for DIR");
  cmd->add_option("--hosts", farm->hosts,
                  "GNU parallel: ssh login file (--sshloginfile; ':' is this machine)")
      ->check(NonEmptyPath);
  cmd->add_flag("--force", farm->force, "Render frames that already have an image too");
}

bool run_render_on_farm(const std::string& dir, const std::string& frames, const FarmArgs& farm) {
  if (farm.status) {
    const FarmStatus s = slurm_status(dir);
    std::printf("%s\n", s.line.c_str());
    report_failures(s.failures);
    if (!s.failures.empty())
      throw PovrayError(std::to_string(s.failures.size()) + " frame(s) failed to render");
    return true;
  }
  if (farm.on.empty()) {
    if (!farm.partition.empty() || farm.frames_per_task || !farm.sbatch_args.empty() ||
        farm.no_wait || !farm.hosts.empty())
      throw InputError(
          "--partition, --frames-per-task, --sbatch-arg, --no-wait and --hosts "
          "need --on slurm|parallel");
    return false;
  }
  FarmRequest request;
  request.scene_dir = dir;
  if (!frames.empty()) request.frames = parse_frame_range(frames, "--frames");
  request.force = farm.force;
  if (farm.frames_per_task) request.frames_per_task = farm.frames_per_task;
  request.toonwater = own_executable();
  // A stop signal stops the farm's tasks (GNU parallel's, or the Slurm job with scancel).
  request.stop = stop_on_signals();

  FarmReport r;
  if (farm.on == "slurm") {
    if (!farm.hosts.empty()) throw InputError("--hosts is for --on parallel");
    SlurmOptions options;
    options.partition = farm.partition;
    options.sbatch_args = farm.sbatch_args;
    options.wait = !farm.no_wait;
    r = render_on_slurm(request, options, print_progress);
    if (farm.no_wait) {
      if (r.job_id.empty())
        std::fprintf(stderr, "render: every frame has its image already\n");
      else
        std::printf("%s\n", r.job_id.c_str());
      return true;
    }
  } else {
    if (farm.hosts.empty()) throw InputError("--on parallel needs --hosts FILE");
    if (!farm.partition.empty() || !farm.sbatch_args.empty() || farm.no_wait)
      throw InputError("--partition, --sbatch-arg and --no-wait are for --on slurm");
    ParallelOptions options;
    options.hosts_file = farm.hosts;
    r = render_on_parallel(request, options, print_progress);
  }
  report_failures(r.failures);
  std::fprintf(stderr,
               "render: %zu frame(s) rendered, %zu skipped (already rendered), %zu failed, "
               "%zu task(s) resubmitted, %.2f s\n",
               r.rendered, r.skipped, r.failures.size(), r.resubmitted_tasks, r.seconds);
  if (!r.failures.empty())
    throw PovrayError(std::to_string(r.failures.size()) + " frame(s) failed to render");
  return true;
}

void add_render_task_command(CLI::App& app) {
  auto dir = std::make_shared<std::string>();
  auto frames = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("render-task", "One render farm task (run by Slurm or GNU parallel)");
  cmd->group("");  // hidden: `render --on` writes these command lines
  cmd->add_option("dir", *dir, "Scene directory")->required()->check(NonEmptyPath);
  cmd->add_option("--frames", *frames, "Frame range A-B")->required();
  cmd->callback([dir, frames] {
    RenderRequest request;
    request.scene_dir = *dir;
    request.frames = parse_frame_range(*frames, "--frames");
    // Slurm ends a cancelled or preempted task with SIGTERM: povray is stopped, nothing partial
    // stays.
    request.stop = stop_on_signals();
    char host[256] = "?";
    ::gethostname(host, sizeof host - 1);
    std::fprintf(stderr, "render-task: frames %s of %s on %s\n", printable(*frames).c_str(),
                 printable(*dir).c_str(), printable(host).c_str());
    const RenderReport r = render_frames_in_one_process(request, nullptr);
    report_failures(r.failures);
    std::fprintf(stderr, "render-task: %zu frame(s) rendered, %zu failed, %.2f s\n", r.rendered,
                 r.failures.size(), r.seconds);
    if (!r.failures.empty())
      throw PovrayError(std::to_string(r.failures.size()) + " frame(s) failed to render");
  });
}

}  // namespace toonwater::cli
