// Running the toonwater program from a test. Only tests labelled `cli` (tests/CMakeLists.txt)
// link it: they are built after the program and find it by TOONWATER_EXECUTABLE.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace toonwater::test {

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs the toonwater executable with the given arguments (no shell involved).
CommandResult run_toonwater(const std::vector<std::string>& args);
// The same for another executable (a copy of toonwater elsewhere, say).
CommandResult run_program(const std::filesystem::path& executable,
                          const std::vector<std::string>& args);

// The shared libraries the toonwater program needs, as the dynamic loader lists them (what ldd
// shows), without running it.
std::string libraries_the_program_loads();

}  // namespace toonwater::test
