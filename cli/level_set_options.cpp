#include "cli/level_set_options.hpp"

#include "cli/validators.hpp"

#include <algorithm>
#include <cctype>

namespace toonwater::cli {

void add_level_set_options(CLI::App& cmd, LevelSetOptions& options) {
  cmd.add_option("--grid", options.grid,
                 ".vdb: the level-set grid to mesh (default: surface, then phi, then the only "
                 "level-set grid)")
      ->check(CLI::Validator(
          [](std::string& name) -> std::string {
            if (name.empty() || name.size() > 256 ||
                std::any_of(name.begin(), name.end(),
                            [](unsigned char c) { return c < 32 || c == 127; }))
              return "a grid name of 1 to 256 printable characters";
            return "";
          },
          "NAME"));
  cmd.add_option("--adaptivity", options.adaptivity,
                 ".vdb: OpenVDB's mesher merges flat cells up to this (0: every cell, the default; "
                 "1: the most)")
      ->check(CLI::Range(0.0, 1.0));
}

void check_level_set_options(const LevelSetOptions& options, const std::string& input) {
  if (options.grid.empty() && options.adaptivity == 0.0) return;
  std::string lower = input;
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (!lower.ends_with(".vdb"))
    throw InputError(input + ": --grid and --adaptivity are for .vdb level sets");
}

}  // namespace toonwater::cli
