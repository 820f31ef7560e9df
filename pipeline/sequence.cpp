#include "pipeline/sequence.hpp"

#include "analyzer/mesh_reader.hpp"

#include <fnmatch.h>

#include <cctype>
#include <charconv>

namespace toonwater {
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
  return begin == end || end - begin > 9
             ? -1
             : to_frame(std::string_view(name).substr(begin, end - begin));
}

// A backslash before one of these makes it literal; before anything else it is itself.
constexpr std::string_view pattern_chars = "#*?[";

bool escapes(std::string_view text, std::size_t i) {
  return text[i] == '\\' && i + 1 < text.size() &&
         pattern_chars.find(text[i + 1]) != std::string_view::npos;
}

// The position of the first of `chars` in `name` that no backslash escapes, or npos.
std::size_t find_unescaped(const std::string& name, std::string_view chars) {
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (escapes(name, i))
      ++i;
    else if (chars.find(name[i]) != std::string_view::npos)
      return i;
  }
  return std::string::npos;
}

// `text` with each escaped pattern character in place of its escape.
std::string unescape(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (escapes(text, i)) ++i;
    out += text[i];
  }
  return out;
}

}  // namespace

Sequence find_sequence(const std::string& pattern, const fs::path& base_dir) {
  const fs::path full = base_dir / pattern;
  const std::string name = full.filename().string();
  const fs::path dir = full.parent_path();
  Sequence seq;

  // An existing file is itself, whatever characters its name holds.
  std::error_code ec;
  if (fs::is_regular_file(full, ec)) {
    seq.single_file = true;
    seq.frames.emplace(0, full);
    return seq;
  }
  const auto hashes = find_unescaped(name, "#");
  const bool glob = find_unescaped(name, "*?[") != std::string::npos;
  if (hashes == std::string::npos && !glob) {
    const fs::path file = dir / unescape(name);
    if (!fs::is_regular_file(file, ec)) throw InputError(file.string() + ": no such file");
    seq.single_file = true;
    seq.frames.emplace(0, file);
    return seq;
  }

  std::size_t hash_end = hashes;
  if (hashes != std::string::npos)
    while (hash_end < name.size() && name[hash_end] == '#') ++hash_end;
  const bool numbered = hashes != std::string::npos;
  const std::string prefix = numbered ? unescape(std::string_view(name).substr(0, hashes)) : "";
  const std::string suffix = numbered ? unescape(std::string_view(name).substr(hash_end)) : "";
  for (const auto& entry : fs::directory_iterator(dir.empty() ? fs::path(".") : dir, ec)) {
    if (!entry.is_regular_file()) continue;
    const std::string file = entry.path().filename().string();
    long frame = -1;
    if (hashes != std::string::npos) {
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
      throw InputError(full.string() + ": frame " + std::to_string(frame) + " matches two files: " +
                       seq.frames[frame].string() + " and " + entry.path().string());
  }
  if (ec) throw InputError(dir.string() + ": cannot list directory: " + ec.message());
  if (seq.frames.empty()) throw InputError(full.string() + ": no file matches the pattern");
  return seq;
}

}  // namespace toonwater
