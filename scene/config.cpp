#include "scene/config.hpp"

#include "scene/config_overrides.hpp"
#include "scene/config_schema.hpp"
#include "scene/toml_guard.hpp"

#include <toml++/toml.h>

#include <cctype>
#include <charconv>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace toonwater {

namespace fs = std::filesystem;

ConfigError key_error(const std::string& key, const std::string& message) {
  return ConfigError("config: '" + key + "' " + message);
}

FrameRange parse_frame_range(const std::string& text, const std::string& key) {
  FrameRange r;
  const char* begin = text.data();
  const char* end = begin + text.size();
  auto [p, ec] = std::from_chars(begin, end, r.first);
  if (ec != std::errc{} || r.first < 0)
    throw key_error(key, "must be a frame range A-B or a frame A");
  r.last = r.first;
  if (p != end) {
    if (*p != '-') throw key_error(key, "must be a frame range A-B or a frame A");
    auto [q, ec2] = std::from_chars(p + 1, end, r.last);
    if (ec2 != std::errc{} || q != end || r.last < r.first)
      throw key_error(key, "must be a frame range A-B with A <= B");
  }
  return r;
}

std::string sanitize_identifier(const std::string& text) {
  std::string out;
  for (char ch : text) {
    if (out.size() == 24) break;
    const auto c = static_cast<unsigned char>(ch);
    out += (c < 128 && std::isalnum(c)) ? ch : '_';
  }
  return out.empty() ? std::string("object") : out;
}

SceneConfig load_config(const ConfigSources& sources) {
  toml::table root;
  fs::path config_dir = fs::current_path();
  if (sources.file) {
    try {
      // Only a regular file: a FIFO would block the run, a device never end.
      std::error_code ec;
      const fs::file_status status = fs::status(*sources.file, ec);
      if (fs::exists(status) && !fs::is_regular_file(status))
        throw ConfigError(sources.file->string() + ": is not a regular file");
      std::ifstream in(*sources.file, std::ios::binary);
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      if (!in) throw ConfigError(sources.file->string() + ": cannot read the file");
      root = parse_toml(text, sources.file->string());
    } catch (const toml::parse_error& e) {
      std::ostringstream msg;
      msg << sources.file->string() << ":" << e.source().begin.line << ": " << e.description();
      throw ConfigError(msg.str());
    }
    config_dir = fs::absolute(*sources.file).parent_path();
  }
  std::size_t file_objects = 0;
  if (root.contains("object")) {
    toml::array* objects = root["object"].as_array();
    if (!objects)
      throw ConfigError(source_location(*root.get("object")) +
                        key_error("object", "must be an array of tables: [[object]]").what());
    file_objects = objects->size();
  }
  if (!sources.object_patterns.empty()) {
    if (!root.contains("object")) root.insert("object", toml::array{});
    for (const auto& pattern : sources.object_patterns) {
      toml::table t;
      t.insert("mesh", pattern);
      root["object"].as_array()->push_back(std::move(t));
    }
  }
  for (const auto& assignment : sources.overrides) apply_override(root, assignment);

  SceneConfig config;
  for (auto&& [k, v] : root) {
    const std::string key(k.str());
    if (key != "object") {
      read_section(key, v, config);
      continue;
    }
    const toml::array& objects = *v.as_array();
    for (std::size_t i = 0; i < objects.size(); ++i) {
      ObjectConfig o = read_object(*objects.get(i), "object." + std::to_string(i));
      o.base_dir = i < file_objects ? config_dir : fs::current_path();
      config.objects.push_back(std::move(o));
    }
  }

  // Object names become POV-Ray identifiers and file names: sanitised and made unique.
  std::set<std::string> used;
  std::map<std::string, int> next_suffix;  // per base: n equal names cost O(n log n), not O(n²)
  for (auto& o : config.objects) {
    std::string base = o.name;
    if (base.empty()) {  // from the file name, without the pattern's # * ? and the digits
      base = fs::path(o.mesh).stem().string();
      while (!base.empty() &&
             std::string_view("#*?[]_-.0123456789").find(base.back()) != std::string_view::npos)
        base.pop_back();
    }
    base = sanitize_identifier(base);
    std::string name = base;
    for (int& n = next_suffix.try_emplace(base, 2).first->second; used.count(name); ++n)
      name = base + "_" + std::to_string(n);
    used.insert(name);
    o.name = name;
  }
  return config;
}

}  // namespace toonwater
