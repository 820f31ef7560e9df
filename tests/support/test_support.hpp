// Helpers shared by the tests: scratch directories, running the toonwater executable, files.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace toonwater::test {

// A fresh empty directory under the system temp dir, removed when the object dies.
class ScratchDir {
 public:
  ScratchDir();
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

// Runs the toonwater executable with the given arguments (no shell involved).
CommandResult run_toonwater(const std::vector<std::string>& args);
// The same for another executable (a copy of toonwater elsewhere, say).
CommandResult run_program(const std::filesystem::path& executable,
                          const std::vector<std::string>& args);

std::string read_text(const std::filesystem::path& path);
void write_text(const std::filesystem::path& path, const std::string& text);

// ../shared beside the project root, or an empty path when it is absent.
std::filesystem::path shared_dir();

}  // namespace toonwater::test
