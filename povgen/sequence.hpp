// Frame sequences: one file, a numbered pattern (`sim/water_####.obj`, where the #s stand for a
// zero-padded frame number of at least that many digits) or a glob (`sim/water_*.obj`, the frame
// number being the last run of digits in the file name). Globs apply to the file name only.
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace toonwater::povgen {

struct Sequence {
  std::map<long, std::filesystem::path> frames;  // frame number -> file
  bool single_file = false;                       // one file: the same for every frame
};

// Throws InputError (mesh_reader.hpp) naming the pattern when nothing matches.
Sequence find_sequence(const std::string& pattern, const std::filesystem::path& base_dir);

}  // namespace toonwater::povgen
