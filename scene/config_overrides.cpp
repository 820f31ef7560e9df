#include "scene/config_overrides.hpp"

#include "scene/config.hpp"
#include "scene/toml_guard.hpp"

#include <charconv>
#include <sstream>
#include <vector>

namespace toonwater {
namespace {

// The value as TOML, or as a string when it is not TOML (a bare word). Parsed without a source
// name, so that errors about it name the key, not a place in a file.
toml::table parse_override_value(const std::string& value) {
  try {
    return parse_toml("v = " + value, "");
  } catch (const toml::parse_error&) {
  } catch (const ConfigError&) {
  }
  toml::table t;
  t.insert("v", value);  // a bare word: a string
  return t;
}

}  // namespace

void apply_override(toml::table& root, const std::string& assignment) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("--set '" + assignment + "': expected key=value");
  const std::string key = assignment.substr(0, eq);
  toml::table parsed = parse_override_value(assignment.substr(eq + 1));

  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string p; std::getline(ss, p, '.');) parts.push_back(p);
  if (parts.size() < 2 || parts.size() > 3)
    throw key_error(key, "is not a known key (use section.key, e.g. water.ior)");

  toml::table* table = &root;
  std::size_t i = 0;
  if (parts[0] == "object") {
    // object.N.key: the N-th object (0-based) of [[object]] and --object, in that order.
    toml::array* objects = root["object"].as_array();
    std::size_t index = 0;
    const auto& n = parts[1];
    // An index too large for size_t fails (ec set) rather than leaving index 0: object 0.
    const auto [end, error] = std::from_chars(n.data(), n.data() + n.size(), index);
    if (parts.size() != 3 || n.empty() || error != std::errc{} || end != n.data() + n.size() ||
        !objects || index >= objects->size() || !objects->get(index)->is_table())
      throw key_error(key, "does not name an object (use object.N.key, N counting from 0)");
    table = objects->get(index)->as_table();
    i = 2;
  }
  for (; i + 1 < parts.size(); ++i) {
    if (!table->contains(parts[i])) table->insert(parts[i], toml::table{});
    table = (*table)[parts[i]].as_table();
    if (!table) throw key_error(key, "does not lead to a table");
  }
  table->insert_or_assign(parts.back(), *parsed.get("v"));
}

}  // namespace toonwater
