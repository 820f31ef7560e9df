// Rendering with GNU parallel: one job per frame range, each `toonwater render-task DIR --frames
// A-B` on a host of the ssh login file (`:` is this machine, without ssh). The scene directory
// must be shared by the hosts (the same path everywhere, e.g. NFS) and toonwater installed at the
// same path. Progress comes from the images in DIR; a job that fails is run once more
// (`--retries 2`, on another host when there is one). Each job's output is kept in
// DIR/.farm/parallel/1/A-B/{stdout,stderr}, GNU parallel's job log in DIR/.farm/parallel.joblog.
#pragma once

#include "render/farm.hpp"

#include <string>

namespace toonwater {

struct ParallelOptions {
  std::string hosts_file;  // GNU parallel's --sshloginfile
  double poll_seconds = 0.5;
};

// Throws InputError for a directory without a scene or a missing hosts file, OutputError when
// GNU parallel cannot be run or fails itself (the message holds the command line).
FarmReport render_on_parallel(const FarmRequest& request, const ParallelOptions& options,
                              const FarmProgressFn& progress);

}  // namespace toonwater
