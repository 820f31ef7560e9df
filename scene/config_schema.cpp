#include "scene/config_schema.hpp"

#include "analyzer/analysis_settings.hpp"
#include "scene/mesh2_writer.hpp"

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace toonwater {

std::string source_location(const toml::node& node) {
  const toml::source_region& source = node.source();
  if (!source.path || source.path->empty() || source.begin.line == 0) return "";
  return *source.path + ":" + std::to_string(source.begin.line) + ": ";
}

namespace {

// ---- how a value is read: its type and range, how its default is written ----

std::string show_range(double lo, double hi) {
  return "from " + show_number(lo) + " to " + show_number(hi);
}

double read_double(const toml::node& node, const std::string& key) {
  std::optional<double> value;
  if (auto i = node.as_integer()) value = static_cast<double>(i->get());
  if (auto f = node.as_floating_point()) value = f->get();
  if (!value) throw key_error(key, "must be a number");
  if (!std::isfinite(*value)) throw key_error(key, "must be finite");
  return *value;
}

struct Number {
  double lo, hi;
  double read(const toml::node& node, const std::string& key) const {
    const double v = read_double(node, key);
    if (v < lo || v > hi)
      throw key_error(key, "must be between " + show_number(lo) + " and " + show_number(hi));
    return v;
  }
  std::string type() const { return "number " + show_range(lo, hi); }
  std::string show(double v) const { return show_number(v); }
};

// A count or a size: a TOML integer, or a float with no fractional part (640.0), never 640.7
// (which would otherwise be truncated in silence). Integers are compared as integers, so no
// large one is rounded through a double on its way.
struct Integer {
  int lo, hi;
  int read(const toml::node& node, const std::string& key) const {
    std::int64_t v = 0;
    if (auto i = node.as_integer()) {
      v = i->get();
    } else if (auto f = node.as_floating_point()) {
      const double d = f->get();
      if (!std::isfinite(d)) throw key_error(key, "must be finite");
      if (d != std::floor(d)) throw key_error(key, "must be a whole number");
      using limits = std::numeric_limits<std::int64_t>;
      v = std::fabs(d) < 1e18 ? static_cast<std::int64_t>(d)
          : d < 0             ? limits::min()
                              : limits::max();
    } else {
      throw key_error(key, "must be a whole number");
    }
    if (v < lo || v > hi)
      throw key_error(key, "must be between " + std::to_string(lo) + " and " + std::to_string(hi));
    return static_cast<int>(v);
  }
  std::string type() const {
    return "whole number from " + std::to_string(lo) + " to " + std::to_string(hi);
  }
  std::string show(int v) const { return std::to_string(v); }
};

struct Boolean {
  bool read(const toml::node& node, const std::string& key) const {
    if (auto b = node.as_boolean()) return b->get();
    throw key_error(key, "must be true or false");
  }
  std::string type() const { return "true or false"; }
  std::string show(bool v) const { return v ? "true" : "false"; }
};

struct Text {
  std::string read(const toml::node& node, const std::string& key) const {
    if (auto s = node.as_string()) return s->get();
    throw key_error(key, "must be a string");
  }
  std::string type() const { return "string"; }
  std::string show(const std::string& v) const { return v.empty() ? "" : "\"" + v + "\""; }
};

// Three numbers in [lo, hi]: colours and vectors.
std::array<double, 3> read_triple(const toml::node& node, const std::string& key, double lo,
                                  double hi, const std::string& what) {
  const toml::array* a = node.as_array();
  if (!a || a->size() != 3) throw key_error(key, "must be " + what);
  std::array<double, 3> out{};
  for (std::size_t i = 0; i < 3; ++i) {
    const double v = read_double(*a->get(i), key);
    if (v < lo || v > hi) throw key_error(key, "must be " + what);
    out[i] = v;
  }
  return out;
}

std::string show_triple(double a, double b, double c) {
  return "[" + show_number(a) + "," + show_number(b) + "," + show_number(c) + "]";
}

struct Colour {
  Color read(const toml::node& node, const std::string& key) const {
    return read_triple(node, key, 0.0, 1.0, type());
  }
  std::string type() const { return "a colour [r, g, b] with components in 0-1"; }
  std::string show(const Color& c) const { return show_triple(c[0], c[1], c[2]); }
};

struct Vector {
  Vec3 read(const toml::node& node, const std::string& key) const {
    // Within what a POV-Ray scene takes (mesh2_writer.hpp): a camera beyond it would put the
    // outline shells, sized by the distance to it, out of reach too.
    const auto t =
        read_triple(node, key, -largest_scene_coordinate, largest_scene_coordinate, type());
    return {t[0], t[1], t[2]};
  }
  std::string type() const { return "a vector [x, y, z] of numbers between -1e18 and 1e18"; }
  std::string show(const Vec3& v) const { return show_triple(v.x(), v.y(), v.z()); }
};

template <class Enum>
struct Keyword {
  std::vector<std::pair<const char*, Enum>> choices;
  Enum read(const toml::node& node, const std::string& key) const {
    const std::string s = Text{}.read(node, key);
    for (const auto& [name, value] : choices)
      if (s == name) return value;
    throw key_error(key, "must be one of " + type());
  }
  std::string type() const {
    std::string names;
    for (const auto& choice : choices)
      names += (names.empty() ? "\"" : " | \"") + std::string(choice.first) + "\"";
    return names;
  }
  std::string show(Enum v) const {
    for (const auto& [name, value] : choices)
      if (v == value) return "\"" + std::string(name) + "\"";
    return "?";
  }
};

struct Frames {
  FrameRange read(const toml::node& node, const std::string& key) const {
    return parse_frame_range(Text{}.read(node, key), key);
  }
  std::string type() const { return "\"A-B\" or \"A\" (frame numbers)"; }
};

// ---- a section: its keys, each with its reader, default and help ----

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};

template <class S>
struct Key {
  std::string name;
  std::string type;
  std::string default_value;
  std::string help;
  std::function<void(S&, const toml::node&, const std::string& key)> read;
};

// A key stored in `member`, read by `reader`. Its default is the member's in a default S, then
// `note` ("(off)"); a member that holds nothing by default (an optional, an empty string) is
// described by `note` alone: what decides its value.
template <class S, class T, class Reader>
Key<S> key(const char* name, T S::*member, Reader reader, const char* help,
           const std::string& note = {}) {
  std::string shown;
  if constexpr (!is_optional<T>::value) shown = reader.show(S{}.*member);
  Key<S> k{name, reader.type(), shown.empty() || note.empty() ? shown + note : shown + " " + note,
           help, nullptr};
  k.read = [member, reader](S& s, const toml::node& v, const std::string& full) {
    s.*member = reader.read(v, full);
  };
  return k;
}

template <class S>
struct Section {
  std::string name;  // "water"; "object" for an [[object]] table
  std::vector<Key<S>> keys;
  // The rules between keys, given the names of the keys the table set.
  std::function<void(S&, const std::set<std::string>& given)> check;
};

const toml::table& as_table(const toml::node& node, const std::string& key) {
  const toml::table* t = node.as_table();
  if (!t) throw ConfigError(source_location(node) + key_error(key, "must be a table").what());
  return *t;
}

template <class S>
void read_keys(const Section<S>& section, const toml::node& node, const std::string& prefix,
               S& out) {
  std::set<std::string> given;
  for (auto&& [k, v] : as_table(node, prefix)) {
    const std::string name(k.str());
    const std::string full = prefix + "." + name;
    const Key<S>* found = nullptr;
    for (const Key<S>& candidate : section.keys)
      if (candidate.name == name) found = &candidate;
    if (!found)
      throw ConfigError(source_location(v) + key_error(full, "is not a known key").what());
    try {
      found->read(out, v, full);
    } catch (const ConfigError& e) {
      throw ConfigError(source_location(v) + e.what());
    }
    given.insert(name);
  }
  // A rule between keys names the table it is in: the error has no one value to point at.
  if (section.check) {
    try {
      section.check(out, given);
    } catch (const ConfigError& e) {
      throw ConfigError(source_location(node) + e.what());
    }
  }
}

// ---- the schema ----

const Section<CameraConfig>& camera_section() {
  using C = CameraConfig;
  static const Section<C> section{
      "camera",
      {key("location", &C::location, Vector{}, "camera position", "framed"),
       key("look_at", &C::look_at, Vector{}, "point looked at", "framed"),
       key("angle", &C::angle, Number{1.0, 170.0}, "horizontal field of view, degrees")},
      [](C& c, const std::set<std::string>&) {
        if (c.location && c.look_at && (*c.location - *c.look_at).norm() == 0.0)
          throw key_error("camera.look_at", "must differ from camera.location");
      }};
  return section;
}

const Section<LightConfig>& light_section() {
  using C = LightConfig;
  static const Section<C> section{
      "light",
      {key("direction", &C::direction, Vector{}, "direction towards the light (parallel rays)",
           "from above-left-front"),
       key("position", &C::position, Vector{}, "a point light instead; excludes direction", "—"),
       key("color", &C::color, Colour{}, "the light's colour")},
      [](C& c, const std::set<std::string>&) {
        if (c.direction && c.position)
          throw key_error("light.position", "excludes light.direction: give one");
        if (c.direction && c.direction->norm() == 0.0)
          throw key_error("light.direction", "must not be zero");
      }};
  return section;
}

const Section<WaterConfig>& water_section() {
  using C = WaterConfig;
  const Number weight{0.0, 10.0}, l_dot_n{-1.0, 1.0}, share{0.0, 1.0};
  static const Section<C> section{
      "water",
      {key("shading", &C::shading,
           Keyword<WaterShading>{{{"toon", WaterShading::toon},
                                  {"gaussian", WaterShading::gaussian},
                                  {"mean", WaterShading::mean}}},
           "the Cartoon Water Shader, or the water coloured by its curvature"),
       key("bright", &C::bright, Colour{}, "the bright band's colour"),
       key("medium", &C::medium, Colour{}, "the medium band's colour"),
       key("dark", &C::dark, Colour{}, "the dark band's colour"),
       key("bands", &C::bands,
           Keyword<BandThresholds>{
               {{"relative", BandThresholds::relative}, {"absolute", BandThresholds::absolute}}},
           "band thresholds around the calm water's L·n, or absolute",
           "(\"absolute\" when `t_bright` or `t_medium` is given)"),
       key("normals", &C::normals,
           Keyword<WaterNormals>{
               {{"smoothed", WaterNormals::smoothed}, {"mesh", WaterNormals::mesh}}},
           "the normals the bands are chosen from: smoothed at the cells' scale and kept above "
           "their noise, or the mesh's own"),
       key("dt_bright", &C::dt_bright, l_dot_n,
           "relative: bright where L·n > calm + dt_bright (unset: at least 3 noise floors)"),
       key("dt_medium", &C::dt_medium, l_dot_n,
           "relative: dark where L·n <= calm + dt_medium (unset: at least 3 noise floors)"),
       key("t_bright", &C::t_bright, l_dot_n, "absolute: bright where L·n > t_bright"),
       key("t_medium", &C::t_medium, l_dot_n, "absolute: dark where L·n <= t_medium"),
       key("ka", &C::ka, weight, "ambient weight"),
       key("kd", &C::kd, weight, "diffuse weight"),
       key("ks", &C::ks, weight, "specular weight (0: no highlight)"),
       key("specular_color", &C::specular_color, Colour{}, "the highlight's colour"),
       key("phong_size", &C::phong_size, Number{1.0, 10000.0}, "n in (R·V)^n"),
       key("reflection", &C::reflection, share, "weight of the reflected ray"),
       key("sky", &C::sky, Colour{}, "what a reflected ray sees where it misses every object",
           "the bright band colour"),
       key("transmit", &C::transmit, share, "share of the refracted ray (0: opaque)"),
       key("ior", &C::ior, Number{1.0, 3.0}, "index of refraction"),
       key("body", &C::body,
           Keyword<WaterBody>{{{"opaque", WaterBody::opaque}, {"clear", WaterBody::clear}}},
           "a closed liquid volume: see-through free surface over an opaque body, or all clear"),
       key("simplify", &C::simplify, Number{0.0, 100.0},
           "simplify the render mesh within this many pixels on screen (0: full mesh)"),
       key("min_patch", &C::min_patch, Number{0.0, 100.0},
           "smallest patch of a band or flow region drawn, radius in pixels (0: every patch)")},
      [](C& c, const std::set<std::string>& given) {
        if (c.t_medium >= c.t_bright)
          throw key_error("water.t_medium", "must be less than water.t_bright");
        if (c.dt_medium >= c.dt_bright)
          throw key_error("water.dt_medium", "must be less than water.dt_bright");
        if ((given.count("t_bright") || given.count("t_medium")) && !given.count("bands"))
          c.bands = BandThresholds::absolute;
        if (given.count("dt_bright") || given.count("dt_medium")) c.bands_above_noise = false;
      }};
  return section;
}

const Section<OutlineConfig>& outline_section() {
  using C = OutlineConfig;
  static const Section<C> section{
      "outline",
      {key("enabled", &C::enabled, Boolean{}, "outline shells for the water and objects"),
       key("width", &C::width, Number{1e-9, 1e9}, "line width: shell offset along the normals",
           "2 (pixels), 0.006 (relative), 0.01 (world)"),
       key("units", &C::units,
           Keyword<WidthUnits>{{{"pixels", WidthUnits::pixels},
                                {"relative", WidthUnits::relative},
                                {"world", WidthUnits::world}}},
           "what the width is measured in"),
       key("color", &C::color, Colour{}, "line colour")},
      nullptr};
  return section;
}

// A setting of the analysis as a [flow] key: its range, refusals, default and help are the
// analysis settings' (analyzer/analysis_settings.hpp), which `toonwater analyze` takes too.
Key<FlowConfig> analysis_key(const AnalysisSetting& setting) {
  const std::string shown =
      setting.is_word() ? "\"" + setting.default_value + "\"" : setting.default_value;
  return {setting.key, setting.type(), shown, setting.help,
          [&setting](FlowConfig& c, const toml::node& v, const std::string& key) {
            if (setting.is_word()) {
              const std::string word = Text{}.read(v, key);
              for (std::size_t i = 0; i < setting.words.size(); ++i)
                if (word == setting.words[i].first) {
                  setting.store_word(c.analysis, i);
                  return;
                }
              throw key_error(key, "must be one of " + setting.type());
            }
            if (!v.is_number())
              throw key_error(
                  key, setting.is_whole_number() ? "must be a whole number" : "must be a number");
            const double value = read_double(v, key);
            if (const std::string why = setting.refusal(value); !why.empty())
              throw key_error(key, why);
            setting.store(c.analysis, value);
          }};
}

const Section<FlowConfig>& flow_section() {
  using C = FlowConfig;
  static const Section<C> section = [] {
    Section<C> flow{
        "flow", {key("enabled", &C::enabled, Boolean{}, "draw the water-flow regions")}, nullptr};
    for (const AnalysisSetting& setting : analysis_settings())
      flow.keys.push_back(analysis_key(setting));
    for (Key<C>& k : std::vector<Key<C>>{
             key("style", &C::style,
                 Keyword<FlowStyle>{{{"regions", FlowStyle::regions},
                                     {"lines", FlowStyle::lines},
                                     {"regions+lines", FlowStyle::regions_and_lines}}},
                 "filled regions, strokes (along narrow crests, around wide regions), or both"),
             key("line_width", &C::line_width, Number{0.1, 100.0}, "stroke width in pixels"),
             key("line_color", &C::line_color, Colour{}, "stroke colour",
                 "region colours (\"lines\"), outline colour (\"regions+lines\")"),
             key("ridge_color", &C::ridge_color, Colour{}, "ridge regions' colour"),
             key("valley_color", &C::valley_color, Colour{}, "valley regions' colour"),
             key("coherence", &C::coherence, Boolean{},
                 "carry regions and strokes from frame to frame")})
      flow.keys.push_back(std::move(k));
    return flow;
  }();
  return section;
}

const Section<ObjectConfig>& object_section() {
  using C = ObjectConfig;
  static const Section<C> section{
      "object",
      {key("name", &C::name, Text{}, "identifier (sanitised, made unique)", "file name"),
       key("mesh", &C::mesh, Text{}, "file or sequence pattern, relative to the config file",
           "required"),
       key("color", &C::color, Colour{}, "the object's colour"),
       key("outline", &C::outline, Boolean{}, "outline shell for this object"),
       key("reflection", &C::reflection,
           Keyword<ReflectionTarget>{{{"concrete", ReflectionTarget::concrete},
                                      {"abstract", ReflectionTarget::abstract},
                                      {"none", ReflectionTarget::none}}},
           "how the water reflects the object")},
      nullptr};
  return section;
}

const Section<ParticlesConfig>& particles_section() {
  using C = ParticlesConfig;
  static const Section<C> section{
      "particles",
      {key("spray", &C::spray, Boolean{}, "draw the spray particles as outlined droplets"),
       key("droplet_size", &C::droplet_size, Number{1.0, 200.0},
           "a droplet's size across in pixels (the frame's median; denser clusters up to twice)"),
       key("max_droplets", &C::max_droplets, Integer{0, 10000},
           "most droplets a frame shows, the ones with most particles"),
       key("foam", &C::foam, Boolean{}, "draw the foam particles as flat patches on the water"),
       key("foam_reach", &C::foam_reach, Number{0.5, 100.0},
           "how far a foam particle's foam reaches, in pixels"),
       key("foam_density", &C::foam_density, Number{0.1, 1000.0},
           "foam particles within a reach that make a patch"),
       key("foam_color", &C::foam_color, Colour{}, "the foam's colour"),
       key("bubbles", &C::bubbles, Boolean{},
           "draw the bubble particles as outlined discs seen through the water"),
       key("bubble_size", &C::bubble_size, Number{1.0, 200.0}, "a bubble's size across in pixels"),
       key("max_bubbles", &C::max_bubbles, Integer{0, 10000},
           "most bubbles a frame shows, the ones with most particles")},
      nullptr};
  return section;
}

const Section<RenderConfig>& render_section() {
  using C = RenderConfig;
  const Integer size{1, 16384};
  static const Section<C> section{
      "render",
      {key("width", &C::width, size, "image width, pixels"),
       key("height", &C::height, size, "image height, pixels"),
       key("quality", &C::quality,
           Keyword<RenderQuality>{{{"draft", RenderQuality::draft},
                                   {"preview", RenderQuality::preview},
                                   {"final", RenderQuality::final}}},
           "preset: size and antialiasing"),
       key("antialias", &C::antialias, Boolean{}, "false: antialiasing off whatever the quality"),
       key("frames", &C::frames, Frames{}, "frames written", "all"),
       key("fps", &C::fps, Integer{1, max_frame_rate},
           "frames per second of the video `toonwater render --video` makes"),
       key("background", &C::background, Colour{}, "background colour")},
      nullptr};
  return section;
}

// Every section with the member of SceneConfig it fills, in the order of the documentation;
// [[object]] tables (a list, read by read_object) have no member.
template <class Fn>
void for_each_section(Fn&& fn) {
  fn(camera_section(), &SceneConfig::camera);
  fn(light_section(), &SceneConfig::light);
  fn(water_section(), &SceneConfig::water);
  fn(outline_section(), &SceneConfig::outline);
  fn(flow_section(), &SceneConfig::flow);
  fn(object_section(), nullptr);
  fn(particles_section(), &SceneConfig::particles);
  fn(render_section(), &SceneConfig::render);
}

}  // namespace

void read_section(const std::string& name, const toml::node& node, SceneConfig& config) {
  bool known = false;
  for_each_section([&](const auto& section, auto member) {
    if constexpr (!std::is_null_pointer_v<decltype(member)>) {
      if (section.name != name) return;
      read_keys(section, node, name, config.*member);
      known = true;
    }
  });
  if (!known)
    throw ConfigError(source_location(node) + key_error(name, "is not a known section").what());
}

ObjectConfig read_object(const toml::node& node, const std::string& prefix) {
  ObjectConfig object;
  read_keys(object_section(), node, prefix, object);
  if (object.mesh.empty())
    throw ConfigError(
        source_location(node) +
        key_error(prefix + ".mesh", "is required (a mesh file or sequence pattern)").what());
  return object;
}

std::vector<ConfigKey> config_keys() {
  std::vector<ConfigKey> keys;
  for_each_section([&](const auto& section, auto) {
    for (const auto& k : section.keys)
      keys.push_back({section.name + "." + k.name, k.type, k.default_value, k.help});
  });
  return keys;
}

}  // namespace toonwater
