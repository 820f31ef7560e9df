// Rendering on a Slurm cluster: one `sbatch --array` job, one array task per frame range, each
// task `toonwater render-task DIR --frames A-B` (one POV-Ray process over the range, images renamed
// into DIR complete). The scene directory must be on a file system the nodes share.
// Waiting, progress comes from the images in DIR and from `squeue` (array tasks still pending or
// running); tasks that ended without all their images (failed, killed, preempted, node failure)
// are resubmitted once as a second array over the missing frames. Each task logs to
// DIR/.farm/slurm-JOB_TASK.log; a failed frame keeps POV-Ray's log as DIR/render_N.log.
#pragma once

#include "render/farm.hpp"

#include <string>
#include <vector>

namespace toonwater {

struct SlurmOptions {
  std::string partition;                 // empty: the cluster's default
  std::vector<std::string> sbatch_args;  // passed to sbatch as they are
  bool wait = true;                      // false: submit and return (FarmReport::job_id)
  double poll_seconds = 1.0;
};

// Throws InputError for a directory without a scene, OutputError when sbatch or squeue cannot be
// run or fail (the message holds the command line and Slurm's own error, e.g. a wrong partition).
FarmReport render_on_slurm(const FarmRequest& request, const SlurmOptions& options,
                           const FarmProgressFn& progress);

// The state of the job last submitted for DIR (DIR/.farm/job): one line, and whether it finished.
struct FarmStatus {
  std::string line;
  bool finished = false;
  std::vector<FrameFailure> failures;  // once finished: the frames without an image
};
FarmStatus slurm_status(const std::filesystem::path& scene_dir);

}  // namespace toonwater
