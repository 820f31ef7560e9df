#include "povgen/config.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace toonwater::povgen {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& key, const std::string& message) {
  throw ConfigError("config: '" + key + "' " + message);
}

// ---- reading typed values; each names its key when the type or range is wrong ----

double read_number(const toml::node& node, const std::string& key) {
  std::optional<double> value;
  if (auto i = node.as_integer()) value = static_cast<double>(i->get());
  if (auto f = node.as_floating_point()) value = f->get();
  if (!value) fail(key, "must be a number");
  if (!std::isfinite(*value)) fail(key, "must be finite");
  return *value;
}

double read_number_in(const toml::node& node, const std::string& key, double lo, double hi) {
  const double v = read_number(node, key);
  if (v < lo || v > hi) {
    std::ostringstream range;
    range << "must be between " << lo << " and " << hi;
    fail(key, range.str());
  }
  return v;
}

// A whole number: 640 or 640.0, never 640.7 (which would otherwise be truncated in silence).
int read_integer_in(const toml::node& node, const std::string& key, int lo, int hi) {
  const double v = read_number_in(node, key, lo, hi);
  if (v != std::floor(v)) fail(key, "must be a whole number");
  return static_cast<int>(v);
}

bool read_bool(const toml::node& node, const std::string& key) {
  if (auto b = node.as_boolean()) return b->get();
  fail(key, "must be true or false");
}

std::string read_string(const toml::node& node, const std::string& key) {
  if (auto s = node.as_string()) return s->get();
  fail(key, "must be a string");
}

std::array<double, 3> read_triple(const toml::node& node, const std::string& key, double lo,
                                  double hi, const char* what) {
  const toml::array* a = node.as_array();
  if (!a || a->size() != 3) fail(key, std::string("must be ") + what);
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double v = read_number(*a->get(i), key);
    if (v < lo || v > hi) fail(key, std::string("must be ") + what);
    out[i] = v;
  }
  return out;
}

Color read_color(const toml::node& node, const std::string& key) {
  return read_triple(node, key, 0.0, 1.0, "a colour [r, g, b] with components in 0-1");
}

Vec3 read_vec3(const toml::node& node, const std::string& key) {
  const auto t = read_triple(node, key, -1e30, 1e30, "a vector [x, y, z] of finite numbers");
  return {t[0], t[1], t[2]};
}

template <class Enum>
Enum read_keyword(const toml::node& node, const std::string& key,
                  std::initializer_list<std::pair<const char*, Enum>> choices) {
  const std::string s = read_string(node, key);
  std::string names;
  for (const auto& [name, value] : choices) {
    if (s == name) return value;
    names += names.empty() ? "" : " | ";
    names += std::string("\"") + name + "\"";
  }
  fail(key, "must be one of " + names);
}

// Visits every key of a table, rejecting keys that `known` does not list.
const toml::table& as_section(const toml::node& node, const std::string& key) {
  const toml::table* t = node.as_table();
  if (!t) fail(key, "must be a table");
  return *t;
}

template <class Fn>
void for_each_key(const toml::table& table, const std::string& prefix,
                  std::initializer_list<const char*> known, Fn&& fn) {
  for (auto&& [k, v] : table) {
    const std::string name(k.str());
    const std::string key = prefix.empty() ? name : prefix + "." + name;
    bool found = false;
    for (const char* n : known) found = found || name == n;
    if (!found) fail(key, "is not a known key");
    fn(name, key, v);
  }
}

void read_camera(const toml::table& t, CameraConfig& c) {
  for_each_key(t, "camera", {"location", "look_at", "angle"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "location") c.location = read_vec3(v, key);
                 if (n == "look_at") c.look_at = read_vec3(v, key);
                 if (n == "angle") c.angle = read_number_in(v, key, 1.0, 170.0);
               });
  if (c.location && c.look_at && (*c.location - *c.look_at).norm() == 0.0)
    fail("camera.look_at", "must differ from camera.location");
}

void read_light(const toml::table& t, LightConfig& c) {
  for_each_key(t, "light", {"direction", "position", "color"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "direction") c.direction = read_vec3(v, key);
                 if (n == "position") c.position = read_vec3(v, key);
                 if (n == "color") c.color = read_color(v, key);
               });
  if (c.direction && c.position) fail("light.position", "excludes light.direction: give one");
  if (c.direction && c.direction->norm() == 0.0) fail("light.direction", "must not be zero");
}

void read_water(const toml::table& t, WaterConfig& c) {
  bool bands_given = false, absolute_given = false;
  for_each_key(t, "water",
               {"shading", "bright", "medium", "dark", "bands", "dt_bright", "dt_medium",
                "t_bright", "t_medium", "ka", "kd", "ks", "specular_color", "phong_size",
                "reflection", "sky", "transmit", "ior", "body", "simplify"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "shading")
                   c.shading = read_keyword<WaterShading>(v, key,
                                                          {{"toon", WaterShading::toon},
                                                           {"gaussian", WaterShading::gaussian},
                                                           {"mean", WaterShading::mean}});
                 if (n == "bright") c.bright = read_color(v, key);
                 if (n == "medium") c.medium = read_color(v, key);
                 if (n == "dark") c.dark = read_color(v, key);
                 if (n == "bands") {
                   c.bands = read_keyword<BandThresholds>(
                       v, key,
                       {{"relative", BandThresholds::relative},
                        {"absolute", BandThresholds::absolute}});
                   bands_given = true;
                 }
                 if (n == "dt_bright") c.dt_bright = read_number_in(v, key, -1.0, 1.0);
                 if (n == "dt_medium") c.dt_medium = read_number_in(v, key, -1.0, 1.0);
                 if (n == "t_bright" || n == "t_medium") absolute_given = true;
                 if (n == "t_bright") c.t_bright = read_number_in(v, key, -1.0, 1.0);
                 if (n == "t_medium") c.t_medium = read_number_in(v, key, -1.0, 1.0);
                 if (n == "sky") c.sky = read_color(v, key);
                 if (n == "body")
                   c.body = read_keyword<WaterBody>(
                       v, key, {{"opaque", WaterBody::opaque}, {"clear", WaterBody::clear}});
                 if (n == "ka") c.ka = read_number_in(v, key, 0.0, 10.0);
                 if (n == "kd") c.kd = read_number_in(v, key, 0.0, 10.0);
                 if (n == "ks") c.ks = read_number_in(v, key, 0.0, 10.0);
                 if (n == "specular_color") c.specular_color = read_color(v, key);
                 if (n == "phong_size") c.phong_size = read_number_in(v, key, 1.0, 10000.0);
                 if (n == "reflection") c.reflection = read_number_in(v, key, 0.0, 1.0);
                 if (n == "transmit") c.transmit = read_number_in(v, key, 0.0, 1.0);
                 if (n == "ior") c.ior = read_number_in(v, key, 1.0, 3.0);
                 if (n == "simplify") c.simplify = read_number_in(v, key, 0.0, 100.0);
               });
  if (c.t_medium >= c.t_bright) fail("water.t_medium", "must be less than water.t_bright");
  if (c.dt_medium >= c.dt_bright) fail("water.dt_medium", "must be less than water.dt_bright");
  if (absolute_given && !bands_given) c.bands = BandThresholds::absolute;
}

void read_outline(const toml::table& t, OutlineConfig& c) {
  for_each_key(t, "outline", {"enabled", "width", "units", "color"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "enabled") c.enabled = read_bool(v, key);
                 if (n == "width") c.width = read_number_in(v, key, 1e-9, 1e9);
                 if (n == "units")
                   c.units = read_keyword<WidthUnits>(v, key,
                                                      {{"pixels", WidthUnits::pixels},
                                                       {"relative", WidthUnits::relative},
                                                       {"world", WidthUnits::world}});
                 if (n == "color") c.color = read_color(v, key);
               });
}

void read_flow(const toml::table& t, FlowConfig& c) {
  for_each_key(t, "flow",
               {"enabled", "criterion", "k_threshold", "k_threshold_relative", "smoothing",
                "min_region", "style", "line_width", "line_color", "ridge_color", "valley_color",
                "coherence", "estimator"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "enabled") c.enabled = read_bool(v, key);
                 if (n == "criterion")
                   c.criterion = read_keyword<FlowCriterion>(
                       v, key, {{"mean", FlowCriterion::mean}, {"paper", FlowCriterion::paper}});
                 if (n == "k_threshold") c.k_threshold = read_number_in(v, key, 1e-30, 1e30);
                 if (n == "k_threshold_relative")
                   c.k_threshold_relative = read_number_in(v, key, 1e-30, 1e30);
                 if (n == "smoothing") c.smoothing = read_integer_in(v, key, 0, 100);
                 if (n == "min_region") c.min_region = read_number_in(v, key, 0.0, 1e30);
                 if (n == "style")
                   c.style = read_keyword<FlowStyle>(v, key,
                                                     {{"regions", FlowStyle::regions},
                                                      {"lines", FlowStyle::lines},
                                                      {"regions+lines", FlowStyle::regions_and_lines}});
                 if (n == "line_width") c.line_width = read_number_in(v, key, 0.1, 100.0);
                 if (n == "line_color") c.line_color = read_color(v, key);
                 if (n == "ridge_color") c.ridge_color = read_color(v, key);
                 if (n == "valley_color") c.valley_color = read_color(v, key);
                 if (n == "coherence") c.coherence = read_bool(v, key);
                 if (n == "estimator")
                   c.estimator = read_keyword<Estimator>(
                       v, key, {{"one-ring", Estimator::one_ring}, {"jet", Estimator::jet}});
               });
}

void read_render(const toml::table& t, RenderConfig& c) {
  for_each_key(t, "render", {"width", "height", "quality", "antialias", "frames", "background"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "width") c.width = read_integer_in(v, key, 1, 16384);
                 if (n == "height") c.height = read_integer_in(v, key, 1, 16384);
                 if (n == "quality")
                   c.quality = read_keyword<RenderQuality>(v, key,
                                                           {{"draft", RenderQuality::draft},
                                                            {"preview", RenderQuality::preview},
                                                            {"final", RenderQuality::final}});
                 if (n == "antialias") c.antialias = read_bool(v, key);
                 if (n == "frames") c.frames = parse_frame_range(read_string(v, key), key);
                 if (n == "background") c.background = read_color(v, key);
               });
}

ObjectConfig read_object(const toml::table& t, const std::string& prefix) {
  ObjectConfig c;
  for_each_key(t, prefix, {"name", "mesh", "color", "outline", "reflection"},
               [&](const std::string& n, const std::string& key, const toml::node& v) {
                 if (n == "name") c.name = read_string(v, key);
                 if (n == "mesh") c.mesh = read_string(v, key);
                 if (n == "color") c.color = read_color(v, key);
                 if (n == "outline") c.outline = read_bool(v, key);
                 if (n == "reflection")
                   c.reflection = read_keyword<ReflectionTarget>(
                       v, key,
                       {{"concrete", ReflectionTarget::concrete},
                        {"abstract", ReflectionTarget::abstract},
                        {"none", ReflectionTarget::none}});
               });
  if (c.mesh.empty()) fail(prefix + ".mesh", "is required (a mesh file or sequence pattern)");
  return c;
}

// ---- what toml++ must not see ----
// Two kinds of text break toml++ 3.3 (Debian 12's) instead of getting a parse error; both were
// found by fuzzing (tests/fuzz):
//  - a dotted key of some 10^5 components ("a.a.a... = 1", "[a.a.a...]"): toml++ nests a table
//    per component and walks and frees the nesting recursively, which overflows the stack;
//  - a non-ASCII character outside a string or comment, or inside a multi-line basic string:
//    toml++'s whitespace test reaches __builtin_unreachable for many code points (é, for one),
//    which is undefined behaviour (marzer/tomlplusplus issues 190 and 295).
// A scene configuration needs neither: its keys nest three levels at most, and TOML keeps
// non-ASCII text to strings and comments. So parse_toml first scans the text: strings (a quote
// opens one only where TOML expects a key or a value) and comments are skipped, the dots of each
// run of key components counted, and non-ASCII bytes rejected where toml++ would classify them.
// As the scan cannot tell strings apart in text that is not TOML, toml++ then parses a copy with
// every non-ASCII byte replaced by '?', which is valid only inside strings and comments: only
// text that passes both reaches toml++ as it is. Values cannot nest deeper than toml++'s own
// limit (TOML_MAX_NESTED_VALUES) with at most max_key_depth levels each.
constexpr int max_key_depth = 16;

// Throws ConfigError "WHERE:LINE: problem" for text toml++ must not parse.
void check_before_parsing(std::string_view text, const std::string& where) {
  std::size_t line = 1;
  const auto reject = [&](const std::string& problem) {
    throw ConfigError(where + ":" + std::to_string(line) + ": " + problem);
  };
  const auto is_ascii = [](char c) { return static_cast<unsigned char>(c) < 0x80; };
  int dots = 0;
  char last = '\n';  // the last character outside strings and comments, not counting blanks
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    const bool opens_string = (c == '"' || c == '\'') &&
                              std::string_view("\n\r.[{,=").find(last) != std::string_view::npos;
    if (c != ' ' && c != '\t') last = c;
    if (opens_string) {  // a string (perhaps a quoted key component): skip it
      const std::size_t quotes = text.substr(i, 3) == std::string(3, c) ? 3 : 1;
      const std::string_view close = text.substr(i, quotes);
      std::size_t j = i + quotes;
      for (; j < text.size() && text.substr(j, quotes) != close; ++j) {
        if (c == '"' && quotes == 3 && !is_ascii(text[j]))
          reject("non-ASCII text in a \"\"\" string (write it in \"...\" or '''...''')");
        if (c == '"' && text[j] == '\\' && j + 1 < text.size()) ++j;  // an escaped character
        if (text[j] == '\n') ++line;
      }
      i = j + quotes - 1;
    } else if (c == '#') {  // a comment: on to the end of the line
      i = std::min(text.find('\n', i), text.size()) - 1;
    } else if (c == '.') {
      if (++dots > max_key_depth)
        reject("keys nest more than " + std::to_string(max_key_depth) + " levels deep");
    } else if (!is_ascii(c)) {
      reject("non-ASCII character outside a string or comment");
    } else if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' ||
                 c == '\t')) {
      dots = 0;
    }
  }
}

// TOML text parsed by toml++ once nothing in it can break toml++ (see above). Throws ConfigError
// or toml::parse_error.
toml::table parse_toml(std::string_view text, std::string_view source) {
  check_before_parsing(text, std::string(source));
  std::string masked(text);
  std::replace_if(masked.begin(), masked.end(),
                  [](char c) { return static_cast<unsigned char>(c) >= 0x80; }, '?');
  if (masked != text) static_cast<void>(toml::parse(masked, source));  // throws if not TOML
  return toml::parse(text, source);
}

// ---- --set key=value ----

toml::table parse_override_value(const std::string& value) {
  try {
    return parse_toml("v = " + value, "--set");
  } catch (const toml::parse_error&) {
  } catch (const ConfigError&) {
  }
  toml::table t;
  t.insert("v", value);  // a bare word: a string
  return t;
}

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
    fail(key, "is not a known key (use section.key, e.g. water.ior)");

  toml::table* table = &root;
  std::size_t i = 0;
  if (parts[0] == "object") {
    // object.N.key: the N-th object (0-based) of [[object]] and --object, in that order.
    toml::array* objects = root["object"].as_array();
    std::size_t index = 0;
    const auto& n = parts[1];
    if (parts.size() != 3 || n.empty() ||
        std::from_chars(n.data(), n.data() + n.size(), index).ptr != n.data() + n.size() ||
        !objects || index >= objects->size() || !objects->get(index)->is_table())
      fail(key, "does not name an object (use object.N.key, N counting from 0)");
    table = objects->get(index)->as_table();
    i = 2;
  }
  for (; i + 1 < parts.size(); ++i) {
    if (!table->contains(parts[i])) table->insert(parts[i], toml::table{});
    table = (*table)[parts[i]].as_table();
    if (!table) fail(key, "does not lead to a table");
  }
  table->insert_or_assign(parts.back(), *parsed.get("v"));
}

}  // namespace

FrameRange parse_frame_range(const std::string& text, const std::string& key) {
  FrameRange r;
  const char* begin = text.data();
  const char* end = begin + text.size();
  auto [p, ec] = std::from_chars(begin, end, r.first);
  if (ec != std::errc{} || r.first < 0) fail(key, "must be a frame range A-B or a frame A");
  r.last = r.first;
  if (p != end) {
    if (*p != '-') fail(key, "must be a frame range A-B or a frame A");
    auto [q, ec2] = std::from_chars(p + 1, end, r.last);
    if (ec2 != std::errc{} || q != end || r.last < r.first)
      fail(key, "must be a frame range A-B with A <= B");
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
      std::ifstream in(*sources.file, std::ios::binary);
      const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
      if (!in) throw ConfigError(sources.file->string() + ": cannot read the file");
      root = parse_toml(text, sources.file->string());
    } catch (const toml::parse_error& e) {
      std::ostringstream msg;
      msg << sources.file->string() << ":" << e.source().begin.line << ": "
          << e.description();
      throw ConfigError(msg.str());
    }
    config_dir = fs::absolute(*sources.file).parent_path();
  }
  std::size_t file_objects = 0;
  if (root.contains("object")) {
    toml::array* objects = root["object"].as_array();
    if (!objects) fail("object", "must be an array of tables: [[object]]");
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
    if (key == "camera") read_camera(as_section(v, key), config.camera);
    else if (key == "light") read_light(as_section(v, key), config.light);
    else if (key == "water") read_water(as_section(v, key), config.water);
    else if (key == "outline") read_outline(as_section(v, key), config.outline);
    else if (key == "flow") read_flow(as_section(v, key), config.flow);
    else if (key == "render") read_render(as_section(v, key), config.render);
    else if (key == "object") {
      const toml::array& objects = *v.as_array();
      for (std::size_t i = 0; i < objects.size(); ++i) {
        const std::string prefix = "object." + std::to_string(i);
        ObjectConfig o = read_object(as_section(*objects.get(i), prefix), prefix);
        o.base_dir = i < file_objects ? config_dir : fs::current_path();
        config.objects.push_back(std::move(o));
      }
    } else {
      fail(key, "is not a known section");
    }
  }

  // Object names become POV-Ray identifiers and file names: sanitised and made unique.
  std::set<std::string> used;
  std::map<std::string, int> next_suffix;  // per base: n equal names cost O(n log n), not O(n²)
  for (auto& o : config.objects) {
    std::string base = o.name;
    if (base.empty()) {  // from the file name, without the pattern's # * ? and the digits
      base = fs::path(o.mesh).stem().string();
      while (!base.empty() && std::string_view("#*?[]_-.0123456789").find(base.back()) !=
                                  std::string_view::npos)
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

}  // namespace toonwater::povgen
