// --grid and --adaptivity: how a .vdb level set becomes a mesh (analyzer/readers/vdb), shared by
// analyze and povgen (for the water).
#pragma once

#include "analyzer/mesh_reader.hpp"

#include <CLI/CLI.hpp>

#include <string>

namespace toonwater::cli {

void add_level_set_options(CLI::App& cmd, LevelSetOptions& options);

// Refuses the options for an input that is not a .vdb file (a path or a sequence pattern):
// given there, they would be silently ignored.
void check_level_set_options(const LevelSetOptions& options, const std::string& input);

}  // namespace toonwater::cli
