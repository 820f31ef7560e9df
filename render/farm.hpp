// Render farms: the frames of a scene directory split into tasks, each task one
// `toonwater render-task DIR --frames A-B` (render_frames_in_one_process), run by Slurm as a job
// array (farm_slurm.cpp) or by GNU parallel over ssh (farm_parallel.cpp). Frames are done when
// their image is in DIR: images are renamed into place complete, so an image there is a finished
// frame, whichever task or machine made it. That is what makes a farm run resumable (frames with
// an image are skipped unless forced) and what progress and the final report count.
#pragma once

#include "render/frame_ranges.hpp"
#include "render/render.hpp"

#include <atomic>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace toonwater {

struct FarmRequest {
  std::filesystem::path scene_dir;
  std::optional<FrameRange> frames;  // default: all frames in scene.ini
  bool force = false;                // render frames that already have an image
  long frames_per_task = 10;
  std::string toonwater;  // the executable the tasks run (the same path on every host)
  const std::atomic<bool>* stop = nullptr;  // set: stop the tasks and throw InterruptedError
};

struct FarmReport {
  std::size_t rendered = 0;            // frames of the request with an image at the end
  std::size_t skipped = 0;             // frames that had an image before (not forced)
  std::vector<FrameFailure> failures;  // frames without an image at the end, by frame
  std::size_t resubmitted_tasks = 0;
  std::string job_id;  // Slurm's job id (the first submission)
  double seconds = 0;
};

// Progress lines for the user ("slurm job 12: 3/6 frames, 2 running, 1 pending").
using FarmProgressFn = std::function<void(const std::string&)>;

// The request's frames that still need rendering, in order.
std::vector<long> frames_to_render(const FarmRequest& request, const SceneFrames& scene);

// The frames a farm run renders, and how many of those asked for it skips because their image
// is already complete.
struct FarmWork {
  std::vector<long> frames;
  std::size_t skipped = 0;
};
FarmWork farm_work(const FarmRequest& request, const SceneFrames& scene);

// How many of `frames` have their image in the scene directory.
std::size_t count_images(const std::filesystem::path& dir, const SceneFrames& scene,
                         const std::vector<long>& frames);

// The frames of `frames` without an image, each with the reason: POV-Ray's message from its
// render_N.log, else `no_log_reason`.
std::vector<FrameFailure> missing_frames(const std::filesystem::path& dir, const SceneFrames& scene,
                                         const std::vector<long>& frames,
                                         const std::string& no_log_reason);

// Removes the hidden temporary directories of render tasks that were killed (they hold no
// finished image), once the farm's tasks have ended: only directories whose names prove them a
// toonwater render's (temporary_name.hpp), on whichever host they were made.
void remove_task_leftovers(const std::filesystem::path& dir);

struct CommandOutput {
  int status = 0;   // exit status, 128 + signal, 127 when it could not be run
  std::string out;  // stdout
  std::string err;  // stderr
};

// Runs argv (no shell) and collects its output.
CommandOutput run_command(const std::vector<std::string>& argv);

// The command line, quoted for a POSIX shell where needed, for error messages and scripts.
std::string shell_quote(const std::string& word);
std::string shell_command(const std::vector<std::string>& argv);

// The farm state of a scene directory (DIR/.farm/job), written when a job is submitted so that
// `toonwater render DIR --status` can report on it later.
struct FarmState {
  std::string scheduler;  // "slurm"
  std::string job_id;
  std::vector<long> frames;  // the frames the job renders
};
void write_farm_state(const std::filesystem::path& dir, const FarmState& state);
std::optional<FarmState> read_farm_state(const std::filesystem::path& dir);

}  // namespace toonwater
