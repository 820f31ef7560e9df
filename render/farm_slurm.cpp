#include "render/farm_slurm.hpp"

#include "common/atomic_file.hpp"
#include "analyzer/mesh_reader.hpp"

#include <chrono>
#include <sstream>
#include <thread>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

struct QueueCounts {
  std::size_t running = 0, pending = 0;
  bool empty() const { return running + pending == 0; }
};

// The job's array tasks still in the queue. A job the controller has forgotten is an empty queue.
QueueCounts query_queue(const std::string& job_id) {
  const std::vector<std::string> argv{"squeue", "-h", "-r", "-j", job_id, "-o", "%T"};
  const CommandOutput r = run_command(argv);
  if (r.status != 0) {
    if (r.err.find("Invalid job id") != std::string::npos) return {};
    throw OutputError("'" + shell_command(argv) + "' failed" +
                      (r.status == 127 ? " (is Slurm installed?)" : "") + ": " +
                      (r.err.empty() ? "exit status " + std::to_string(r.status) : r.err));
  }
  QueueCounts counts;
  std::istringstream lines(r.out);
  for (std::string state; std::getline(lines, state);) {
    if (state == "RUNNING" || state == "COMPLETING")
      ++counts.running;
    else if (!state.empty())
      ++counts.pending;
  }
  return counts;
}

// Writes the task list and batch script of submission `round`, submits them, returns the job id.
std::string submit(const fs::path& dir, const std::vector<FrameRange>& tasks, int round,
                   const FarmRequest& request, const SlurmOptions& options) {
  const fs::path farm = dir / ".farm";
  std::error_code ec;
  fs::create_directories(farm, ec);
  if (ec) throw OutputError("cannot create " + farm.string() + ": " + ec.message());
  const std::string round_name = std::to_string(round);
  const fs::path task_list = farm / ("slurm-tasks-" + round_name + ".txt");
  const fs::path script = farm / ("slurm-task-" + round_name + ".sh");
  std::string lines;
  for (const auto& t : tasks) lines += format_range(t) + "\n";
  write_file_atomically(task_list, lines);
  // Array task i renders line i + 1 of the task list.
  write_file_atomically(
      script,
      "#!/bin/sh\n# Written by toonwater render --on slurm: one array task, one frame range.\n"
      "range=$(sed -n \"$((SLURM_ARRAY_TASK_ID + 1))p\" " +
          shell_quote(task_list.string()) + ")\nexec " + shell_quote(request.toonwater) +
          " render-task " + shell_quote(dir.string()) + " --frames \"$range\"\n");

  std::vector<std::string> argv{"sbatch",
                                "--parsable",
                                "--job-name=toonwater-render",
                                "--array=0-" + std::to_string(tasks.size() - 1),
                                "--output=" + (farm / "slurm-%A_%a.log").string(),
                                "--chdir=" + dir.string()};
  if (!options.partition.empty()) argv.push_back("--partition=" + options.partition);
  argv.insert(argv.end(), options.sbatch_args.begin(), options.sbatch_args.end());
  argv.push_back(script.string());
  const CommandOutput r = run_command(argv);
  std::string err = r.err;
  while (!err.empty() && (err.back() == '\n' || err.back() == '\r')) err.pop_back();
  if (r.status == 127)
    throw OutputError("cannot run '" + shell_command(argv) +
                      "' (is Slurm installed? sbatch not found)");
  if (r.status != 0)
    throw OutputError("'" + shell_command(argv) + "' failed: " +
                      (err.empty() ? "exit status " + std::to_string(r.status) : err));
  // --parsable prints "jobid" or "jobid;cluster".
  std::string id = r.out.substr(0, r.out.find_first_of(";\n"));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos)
    throw OutputError("'" + shell_command(argv) + "' printed no job id: " + r.out);
  return id;
}

// Waits until no task of `job_id` is left in the queue, reporting progress as it changes.
void wait_for_job(const std::string& job_id, const fs::path& dir, const SceneFrames& scene,
                  const std::vector<long>& frames, const SlurmOptions& options,
                  const FarmProgressFn& progress, const std::atomic<bool>* stop) {
  std::string last_line;
  for (;;) {
    if (stop && stop->load()) {
      // scancel sends the tasks SIGTERM: each stops POV-Ray and leaves nothing partial.
      const CommandOutput cancel = run_command({"scancel", job_id});
      if (cancel.status != 0)
        throw OutputError(dir.string() + ": interrupted, but 'scancel " + job_id +
                          "' failed: " + cancel.err);
      throw InterruptedError(dir.string() + ": interrupted: slurm job " + job_id +
                             " cancelled; the frames rendered so far are kept");
    }
    const QueueCounts q = query_queue(job_id);
    const std::string line =
        "slurm job " + job_id + ": " + std::to_string(count_images(dir, scene, frames)) + "/" +
        std::to_string(frames.size()) + " frames, " + std::to_string(q.running) +
        " task(s) running, " + std::to_string(q.pending) + " pending";
    if (progress && line != last_line) progress(line);
    last_line = line;
    if (q.empty()) return;
    std::this_thread::sleep_for(std::chrono::duration<double>(options.poll_seconds));
  }
}

}  // namespace

FarmReport render_on_slurm(const FarmRequest& request, const SlurmOptions& options,
                           const FarmProgressFn& progress) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = fs::absolute(request.scene_dir);
  const SceneFrames scene = read_scene_frames(dir);
  const auto [frames, skipped] = farm_work(request, scene);
  FarmReport report;
  report.skipped = skipped;
  if (!frames.empty()) {
    const std::vector<FrameRange> tasks = ranges_of_at_most(frames, request.frames_per_task);
    report.job_id = submit(dir, tasks, 0, request, options);
    write_farm_state(dir, {"slurm", report.job_id, frames});
    if (progress)
      progress("slurm job " + report.job_id + ": " + std::to_string(tasks.size()) +
               " task(s) over " + std::to_string(frames.size()) + " frame(s) submitted");
    if (!options.wait) return report;
    wait_for_job(report.job_id, dir, scene, frames, options, progress, request.stop);

    // Tasks that ended without all their images: once more, over the missing frames only.
    std::vector<long> missing;
    for (const auto& m : missing_frames(dir, scene, frames, "")) missing.push_back(m.frame);
    if (!missing.empty()) {
      const std::vector<FrameRange> retry = ranges_of_at_most(missing, request.frames_per_task);
      remove_task_leftovers(dir);
      const std::string retry_id = submit(dir, retry, 1, request, options);
      report.resubmitted_tasks = retry.size();
      write_farm_state(dir, {"slurm", retry_id, frames});
      if (progress)
        progress("slurm job " + report.job_id + ": " + std::to_string(missing.size()) +
                 " frame(s) missing after the tasks ended; resubmitted as job " + retry_id + " (" +
                 std::to_string(retry.size()) + " task(s))");
      wait_for_job(retry_id, dir, scene, frames, options, progress, request.stop);
    }
    remove_task_leftovers(dir);
  }
  report.failures = missing_frames(
      dir, scene, frames, "the task ended without its image (task logs: .farm/slurm-*.log)");
  report.rendered = frames.size() - report.failures.size();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return report;
}

FarmStatus slurm_status(const fs::path& scene_dir) {
  const fs::path dir = fs::absolute(scene_dir);
  const SceneFrames scene = read_scene_frames(dir);
  const auto state = read_farm_state(dir);
  if (!state) throw InputError(dir.string() + ": no farm job was submitted for this scene");
  if (state->scheduler != "slurm")
    throw InputError(dir.string() + ": the last farm run used " + state->scheduler);
  const QueueCounts q = query_queue(state->job_id);
  FarmStatus status;
  status.finished = q.empty();
  status.line = "slurm job " + state->job_id + (status.finished ? " finished" : "") + ": " +
                std::to_string(count_images(dir, scene, state->frames)) + "/" +
                std::to_string(state->frames.size()) + " frames, " + std::to_string(q.running) +
                " task(s) running, " + std::to_string(q.pending) + " pending";
  if (status.finished)
    status.failures =
        missing_frames(dir, scene, state->frames,
                       "the task ended without its image (task logs: .farm/slurm-*.log)");
  return status;
}

}  // namespace toonwater
