// Frame sequences: one file, a numbered pattern (`sim/water_####.obj`, where the #s stand for a
// zero-padded frame number of at least that many digits) or a glob (`sim/water_*.obj`, the frame
// number being the last run of digits in the file name). Globs apply to the file name only.
// An existing file is always taken as itself, even when its name holds # * ? or [. In a
// pattern, a backslash before one of these four makes it literal (any other backslash is
// itself): `sim/run\#2_####.obj` is the sequence
// run#2_0001.obj, run#2_0002.obj, ... (in a shell, quote it: 'sim/run\#2_####.obj').
#pragma once

#include <filesystem>
#include <map>
#include <string>

namespace toonwater {

struct Sequence {
  std::map<long, std::filesystem::path> frames;  // frame number -> file
  bool single_file = false;                      // one file: the same for every frame
};

// Throws InputError (mesh_reader.hpp) naming the pattern when nothing matches.
Sequence find_sequence(const std::string& pattern, const std::filesystem::path& base_dir);

}  // namespace toonwater
