#include "tests/support/test_support.hpp"

#include "common/temporary_name.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace toonwater::test {

namespace fs = std::filesystem;

ScratchDir::ScratchDir() {
  static std::atomic<int> counter{0};
  path_ = fs::temp_directory_path() /
          ("toonwater-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ignored;
  fs::remove_all(path_, ignored);
}

ScopedEnvironmentVariable::ScopedEnvironmentVariable(std::string name, const std::string& value)
    : name_(std::move(name)) {
  if (const char* before = std::getenv(name_.c_str())) before_ = before;
  ::setenv(name_.c_str(), value.c_str(), 1);
}

ScopedEnvironmentVariable::~ScopedEnvironmentVariable() {
  if (before_)
    ::setenv(name_.c_str(), before_->c_str(), 1);
  else
    ::unsetenv(name_.c_str());
}

std::string path_value_with_first(const fs::path& directory) {
  const char* path = std::getenv("PATH");
  return directory.string() + ":" + (path ? path : "/usr/bin:/bin");
}

ScopedEnvironmentVariable path_with_first(const fs::path& directory) {
  return ScopedEnvironmentVariable("PATH", path_value_with_first(directory));
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string());
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> operator+(std::vector<std::string> a, const std::vector<std::string>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

std::vector<std::string> entries(const fs::path& directory) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(directory))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

fs::path shared_dir() {
  const fs::path dir = TOONWATER_SHARED_DIR;
  return fs::is_directory(dir / "data") ? dir : fs::path{};
}

double hue(double r, double g, double b) {
  const double hi = std::max({r, g, b}), lo = std::min({r, g, b}), c = hi - lo;
  if (c <= 0) return 0;
  const double h = hi == r   ? std::fmod((g - b) / c, 6.0)
                   : hi == g ? (b - r) / c + 2
                             : (r - g) / c + 4;
  return std::fmod(60 * h + 360, 360);
}

double hue_distance(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 360 - d);
}

std::string temporary_name_of_a_gone_process(const std::string& name) {
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("pipe failed");
  const pid_t child = ::fork();
  if (child == 0) {
    const std::string made = temporary_name(name);
    const ssize_t written = ::write(fds[1], made.data(), made.size());
    ::_exit(written == static_cast<ssize_t>(made.size()) ? 0 : 1);
  }
  ::close(fds[1]);
  std::string made;
  char buf[512];
  for (ssize_t n; (n = ::read(fds[0], buf, sizeof buf)) > 0;)
    made.append(buf, static_cast<std::size_t>(n));
  ::close(fds[0]);
  int status = 0;
  ::waitpid(child, &status, 0);
  if (made.empty()) throw std::runtime_error("the child made no name");
  return made;
}

std::string wwp_bytes(const std::vector<std::pair<int, Vec3>>& particles) {
  std::vector<std::uint32_t> through(256, 0);
  for (const auto& [id, p] : particles)
    for (int b = id; b < 256; ++b) ++through[static_cast<std::size_t>(b)];
  std::string bytes;
  for (const std::uint32_t t : through) {
    const std::uint32_t stored = t - 1;  // 0xFFFFFFFF while none
    bytes.append(reinterpret_cast<const char*>(&stored), 4);
  }
  std::vector<std::pair<int, Vec3>> sorted = particles;
  std::stable_sort(sorted.begin(), sorted.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [id, p] : sorted)
    for (int axis = 0; axis < 3; ++axis) {
      const float f = static_cast<float>(p[axis]);
      bytes.append(reinterpret_cast<const char*>(&f), 4);
    }
  return bytes;
}

}  // namespace toonwater::test
