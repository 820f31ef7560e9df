#include "povgen/sequence.hpp"

#include "analyzer/mesh_reader.hpp"

#include <fnmatch.h>

#include <cctype>
#include <charconv>

namespace toonwater::povgen {
namespace {

namespace fs = std::filesystem;

bool is_digits(std::string_view s) {
  if (s.empty()) return false;
  for (char c : s)
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  return true;
}

long to_frame(std::string_view digits) {
  long n = 0;
  std::from_chars(digits.data(), digits.data() + digits.size(), n);
  return n;
}

// The last run of digits in a file name, or -1.
long last_number(const std::string& name) {
  std::size_t end = name.size();
  while (end > 0 && !std::isdigit(static_cast<unsigned char>(name[end - 1]))) --end;
  std::size_t begin = end;
  while (begin > 0 && std::isdigit(static_cast<unsigned char>(name[begin - 1]))) --begin;
  return begin == end || end - begin > 9 ? -1 : to_frame(std::string_view(name).substr(begin, end - begin));
}

}  // namespace

Sequence find_sequence(const std::string& pattern, const fs::path& base_dir) {
  const fs::path full = base_dir / pattern;
  const std::string name = full.filename().string();
  const fs::path dir = full.parent_path();
  Sequence seq;

  const auto hashes = name.find('#');
  const bool glob = name.find_first_of("*?[") != std::string::npos;
  if (hashes == std::string::npos && !glob) {
    if (!fs::is_regular_file(full)) throw InputError(full.string() + ": no such file");
    seq.single_file = true;
    seq.frames.emplace(0, full);
    return seq;
  }

  std::size_t hash_end = hashes;
  if (hashes != std::string::npos)
    while (hash_end < name.size() && name[hash_end] == '#') ++hash_end;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir.empty() ? fs::path(".") : dir, ec)) {
    if (!entry.is_regular_file()) continue;
    const std::string file = entry.path().filename().string();
    long frame = -1;
    if (hashes != std::string::npos) {
      const std::string prefix = name.substr(0, hashes), suffix = name.substr(hash_end);
      if (file.size() < prefix.size() + suffix.size() + (hash_end - hashes)) continue;
      if (file.compare(0, prefix.size(), prefix) != 0) continue;
      if (file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
      const std::string_view digits =
          std::string_view(file).substr(prefix.size(), file.size() - prefix.size() - suffix.size());
      if (!is_digits(digits) || digits.size() > 9) continue;
      frame = to_frame(digits);
    } else {
      if (::fnmatch(name.c_str(), file.c_str(), FNM_PERIOD) != 0) continue;
      frame = last_number(entry.path().stem().string());
      if (frame < 0) continue;
    }
    if (!seq.frames.emplace(frame, entry.path()).second)
      throw InputError(full.string() + ": frame " + std::to_string(frame) +
                       " matches two files: " + seq.frames[frame].string() + " and " +
                       entry.path().string());
  }
  if (ec) throw InputError(dir.string() + ": cannot list directory: " + ec.message());
  if (seq.frames.empty()) throw InputError(full.string() + ": no file matches the pattern");
  return seq;
}

}  // namespace toonwater::povgen
