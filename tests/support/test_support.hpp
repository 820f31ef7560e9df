// Helpers shared by the tests: scratch directories, files, ../shared. Running the toonwater
// program: run_toonwater.hpp.
#pragma once

#include "analyzer/mesh.hpp"

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
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

// An environment variable set to `value` for the programs a test starts, until the object dies;
// then it is what it was before (unset, if it was). Keeps a test's PATH from the tests after it
// in the same process.
class ScopedEnvironmentVariable {
 public:
  ScopedEnvironmentVariable(std::string name, const std::string& value);
  ~ScopedEnvironmentVariable();
  ScopedEnvironmentVariable(const ScopedEnvironmentVariable&) = delete;
  ScopedEnvironmentVariable& operator=(const ScopedEnvironmentVariable&) = delete;

 private:
  std::string name_;
  std::optional<std::string> before_;
};

// The value of PATH with `directory` before the test's own PATH.
std::string path_value_with_first(const std::filesystem::path& directory);
// PATH with `directory` first, until the object dies.
[[nodiscard]] ScopedEnvironmentVariable path_with_first(const std::filesystem::path& directory);

std::string read_text(const std::filesystem::path& path);

// The arguments `a`, then `b` (command lines built from parts).
std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b);

// The names of the entries of `directory` (hidden ones included), sorted.
std::vector<std::string> entries(const std::filesystem::path& directory);
void write_text(const std::filesystem::path& path, const std::string& text);

// A whitewater file as FLIP Fluids writes it (analyzer/particles.hpp): the id table
// (through-counts minus one), then the positions sorted by id; `particles` are {id, position}.
std::string wwp_bytes(const std::vector<std::pair<int, Vec3>>& particles);

// ../shared beside the project root, or an empty path when it is absent.
std::filesystem::path shared_dir();

// The hue of a colour in degrees, 0 to 360 (0 for a grey), and the distance of two hues round
// the colour wheel.
double hue(double r, double g, double b);
double hue_distance(double a, double b);

// A temporary name of `name` (common/temporary_name.hpp) as a process that has since ended
// made it: what a killed run leaves behind.
std::string temporary_name_of_a_gone_process(const std::string& name);

}  // namespace toonwater::test
