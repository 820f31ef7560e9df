// The render farm options of `toonwater render` (render_farm_command.cpp).
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

namespace toonwater::cli {

struct FarmArgs {
  std::string on;  // "", "slurm", "parallel"
  std::string partition;
  long frames_per_task = 0;  // 0: the default
  std::vector<std::string> sbatch_args;
  bool no_wait = false, status = false, force = false;
  std::string hosts;
};

void add_render_farm_options(CLI::App* cmd, const std::shared_ptr<FarmArgs>& farm);

// Runs `render` on a farm (or --status) and returns true, or returns false when no farm option
// was given (a local render).
bool run_render_on_farm(const std::string& dir, const std::string& frames, const FarmArgs& farm);

}  // namespace toonwater::cli
