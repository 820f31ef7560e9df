// The analysis settings (analyzer/analysis_settings.hpp) as `toonwater analyze` options: one
// option per setting, its help, default and range check taken from the settings' table.
#pragma once

#include "analyzer/analysis_settings.hpp"

#include <CLI/CLI.hpp>

namespace toonwater::cli {

// Adds --criterion, --k-threshold, ... to `cmd`, each storing into `settings`.
void add_analysis_options(CLI::App& cmd, AnalysisSettings& settings);

}  // namespace toonwater::cli
