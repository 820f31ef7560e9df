// Each subcommand registers its options and its run function on the application.
#pragma once

#include <CLI/CLI.hpp>

namespace toonwater::cli {

void add_analyze_command(CLI::App& app);
void add_povgen_command(CLI::App& app);
void add_render_command(CLI::App& app);
void add_render_task_command(CLI::App& app);
void add_simulate_command(CLI::App& app);
void add_report_command(CLI::App& app);

}  // namespace toonwater::cli
