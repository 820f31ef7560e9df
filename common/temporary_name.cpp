// Temporary names with a check; stated in temporary_name.hpp.
#include "common/temporary_name.hpp"

#include <signal.h>
#include <sys/random.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cstdint>
#include <cstdio>

namespace toonwater {
namespace {

constexpr std::string_view kMarker = ".tmp-";
constexpr std::size_t kMaxName = 100;

std::uint64_t fnv1a(std::string_view text) {
  std::uint64_t h = 14695981039346656037ull;
  for (const unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::string hex(std::uint64_t value, int digits) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%0*llx", digits, static_cast<unsigned long long>(value));
  return std::string(buf, static_cast<std::size_t>(digits));
}

const std::string& this_host() {
  static const std::string host = [] {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0) name[0] = '\0';
    return hex(fnv1a(name) & 0xffffffffull, 8);
  }();
  return host;
}

std::uint64_t random_bits() {
  std::uint64_t r = 0;
  if (::getrandom(&r, sizeof r, 0) == static_cast<ssize_t>(sizeof r)) return r;
  // No entropy source: the clock and the address of a local differ between processes.
  const auto now = std::chrono::steady_clock::now().time_since_epoch().count();
  return fnv1a(std::to_string(now) + std::to_string(reinterpret_cast<std::uintptr_t>(&r)));
}

// The check of a temporary of `name` with the fields `fields` ("H-P-R").
std::string check(std::string_view name, std::string_view fields) {
  std::string text = "toonwater temporary\n";
  text += name;
  text += '\n';
  text += fields;
  return hex(fnv1a(text) & 0xffffffffull, 8);
}

// The parts of a temporary name: NAME, H, P (parsed), and whether the check holds.
struct Parsed {
  std::string_view name, host;
  pid_t pid = 0;
};
bool parse(std::string_view filename, Parsed& out) {
  if (filename.size() < 2 || filename[0] != '.') return false;
  const std::size_t marker = filename.rfind(kMarker);
  if (marker == std::string_view::npos || marker < 1) return false;
  const std::string_view name = filename.substr(1, marker - 1);
  const std::string_view rest = filename.substr(marker + kMarker.size());
  // H(8) - P - R(16) - C(8)
  const std::size_t last = rest.rfind('-');
  if (last == std::string_view::npos) return false;
  const std::string_view fields = rest.substr(0, last), given = rest.substr(last + 1);
  if (given.size() != 8 || name.size() > kMaxName || check(name, fields) != given) return false;
  const std::size_t first = fields.find('-'), second = fields.rfind('-');
  if (first != 8 || second == first) return false;
  const std::string_view pid = fields.substr(first + 1, second - first - 1);
  const auto [end, error] = std::from_chars(pid.data(), pid.data() + pid.size(), out.pid);
  if (error != std::errc{} || end != pid.data() + pid.size() || out.pid <= 0) return false;
  out.name = name;
  out.host = fields.substr(0, 8);
  return true;
}

}  // namespace

std::string temporary_name(std::string_view name) {
  name = name.substr(0, kMaxName);
  const std::string fields =
      this_host() + "-" + std::to_string(::getpid()) + "-" + hex(random_bits(), 16);
  std::string out = ".";
  out += name;
  out += kMarker;
  out += fields + "-" + check(name, fields);
  return out;
}

bool is_own_temporary(std::string_view filename, std::string* name) {
  Parsed parsed;
  if (!parse(filename, parsed)) return false;
  if (name) *name = std::string(parsed.name);
  return true;
}

bool is_stale_temporary(std::string_view filename) {
  Parsed parsed;
  if (!parse(filename, parsed) || parsed.host != this_host()) return false;
  if (parsed.pid == ::getpid()) return false;
  return ::kill(parsed.pid, 0) != 0 && errno == ESRCH;
}

}  // namespace toonwater
