// Scene configuration: every key of scene.toml, with the paper's choices as defaults.
//
// Loaded from TOML (toml++, behind scene/toml_guard.hpp); `--set key=value` overrides any key
// before validation (scene/config_overrides.hpp). Every key is read through one table
// (scene/config_schema.hpp) that gives its type, range, default and help once. Unknown keys and
// values of the wrong type or out of range are errors naming the key (ConfigError), and the file
// and line where the value comes from a file. Only validated values leave this module: finite
// numbers, whole numbers where a count or a size is meant, colours in [0, 1], known keywords and
// object names reduced to POV-Ray identifiers.
//
// Positions and directions are in the input's axes (the meshes' own coordinates); the scene
// writer maps them to POV-Ray's frame.
#pragma once

#include "analyzer/analysis_settings.hpp"

#include "analyzer/mesh.hpp"
#include "common/frame_range.hpp"
#include "scene/render_presets.hpp"

#include <array>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "config: 'KEY' MESSAGE", the form of every error about one key.
ConfigError key_error(const std::string& key, const std::string& message);

using Color = std::array<double, 3>;  // sRGB in [0, 1], as picked on screen

struct CameraConfig {
  std::optional<Vec3> location;  // default: framed on the water and objects of every frame
  std::optional<Vec3> look_at;   // default: framed likewise
  double angle = 40.0;           // horizontal field of view, degrees
};

struct LightConfig {
  std::optional<Vec3> direction;  // towards the light (a sun): parallel light
  std::optional<Vec3> position;   // a point light; excludes direction
  Color color{1.0, 1.0, 1.0};
};

// Cartoon Water Shader (paper eq. 2-3).
// How the water is drawn: the Cartoon Water Shader, or coloured by its Gaussian or mean
// curvature with the curvature maps' diverging colour map (analyzer/colormap.hpp) over
// a range shared by the whole sequence — a view of surfaces that are not height fields.
enum class WaterShading { toon, gaussian, mean };

// Where the water's band thresholds come from: offsets from the calm water's L·n (the light
// against the up axis), so that calm water is the medium band and ripples show; or absolute
// values of L·n.
enum class BandThresholds { relative, absolute };

// How a see-through closed liquid volume (free surface, walls and floor in one mesh) is drawn:
// opaque: the free surface (faces with n·up > 0.1) is see-through, the walls and floor are an
// opaque body in flat bands, so objects leave no ghost images on the walls and no ray bounces
// around inside; clear: the whole volume is see-through (a body of water seen from all sides,
// a water creature), its outline shell kept on the free surface only.
enum class WaterBody { opaque, clear };

// The normals the water's bands are chosen from: smoothed, the flow stage's shading normals,
// smoothed over the free surface at the scale of the cells and measured for their noise floor
// (flow_regions.hpp), which the relative band limits keep above; mesh, the mesh's own
// angle-weighted vertex normals, for a clean surface (synthetic, or smooth already) whose shape
// is all signal.
enum class WaterNormals { smoothed, mesh };

struct WaterConfig {
  WaterShading shading = WaterShading::toon;
  Color bright{0.36, 0.64, 0.88};
  Color medium{0.20, 0.46, 0.76};
  Color dark{0.08, 0.26, 0.56};
  // Default: relative, or absolute when t_bright or t_medium is given.
  BandThresholds bands = BandThresholds::relative;
  WaterNormals normals = WaterNormals::smoothed;
  double dt_bright = 0.05;   // relative: bright where L·n > calm + dt_bright
  double dt_medium = -0.05;  // relative: dark where L·n <= calm + dt_medium
  // Relative limits widen past the water's normal noise (scene_writer.hpp) unless dt_bright or
  // dt_medium is given: set by the schema, no key of its own.
  bool bands_above_noise = true;
  double t_bright = 0.7;  // absolute (and objects, always): L·n above this: bright band
  double t_medium = 0.2;  // L·n above this (and not bright): medium band; else dark
  double ka = 0.2;
  double kd = 0.8;
  double ks = 0.5;
  Color specular_color{1.0, 1.0, 1.0};
  double phong_size = 40.0;
  double reflection = 0.2;
  // What a reflected ray sees where it misses every object, flat; default: the bright band.
  std::optional<Color> sky;
  double transmit = 0.4;
  double ior = 1.33;
  WaterBody body = WaterBody::opaque;
  // The render mesh is simplified while no surface point moves more than this many pixels on
  // screen (scene/simplify.hpp); 0 writes the full mesh.
  double simplify = 0.5;
  // Patches of a band or flow region smaller than a disc of this radius in pixels, or than the
  // shading's smoothing scale, take the colour around them (scene/toon_islands.hpp); 0 keeps
  // every patch.
  double min_patch = 2.0;
};

// pixels: of an image render.width wide, each shell vertex offset by the size of a pixel at its
// depth from the camera, so lines are even across objects and depth; relative: fraction of the
// mesh's bounding-box diagonal; world: scene units.
enum class WidthUnits { pixels, relative, world };

// The outline's width when none is given in pixels, and a droplet's made on screen (whose
// outline has no size in scene units).
inline constexpr double kDefaultOutlinePixels = 2.0;

struct OutlineConfig {
  bool enabled = true;
  std::optional<double> width;  // default: 2 pixels, 0.006 relative, 0.01 world
  WidthUnits units = WidthUnits::pixels;
  Color color{0.0, 0.0, 0.0};
};

// How flow regions are drawn: filled (regions), as strokes along their contours (lines), or
// both (analyzer/flow_lines.hpp).
enum class FlowStyle { regions, lines, regions_and_lines };

// The water-flow regions (analyzer/flow_regions.hpp): how they are found, the analysis settings
// that `toonwater analyze` takes too (analyzer/analysis_settings.hpp), and how they are drawn.
struct FlowConfig {
  bool enabled = true;
  AnalysisSettings analysis;
  FlowStyle style = FlowStyle::regions;
  double line_width = 2.0;  // pixels
  std::optional<Color>
      line_color;  // default: the region colours (lines), the outline colour (both)
  Color ridge_color{1.0, 1.0, 1.0};
  Color valley_color{0.02, 0.06, 0.22};
  bool coherence = true;  // carry regions and strokes from frame to frame (flow_coherence.hpp,
                          // stroke_persistence.hpp)
};

enum class ReflectionTarget { concrete, abstract, none };

struct ObjectConfig {
  std::string name;  // a POV-Ray identifier fragment: [A-Za-z0-9_], unique among objects
  std::string mesh;  // a file or a numbered sequence pattern, resolved against base_dir
  std::filesystem::path base_dir;
  Color color{0.92, 0.45, 0.18};
  bool outline = true;
  ReflectionTarget reflection = ReflectionTarget::concrete;
};

// Secondary particles (povgen --particles): the spray drawn as a few outlined droplets
// (scene/spray_droplets.hpp), the foam as flat patches on the water (scene/foam_patches.hpp),
// the bubbles as a few outlined discs seen through the water (scene/bubble_writer.hpp).
struct ParticlesConfig {
  bool spray = true;
  double droplet_size = 8.0;  // pixels across, at the frame's median droplet
  int max_droplets = 40;      // a frame's most salient droplets
  bool foam = true;
  double foam_reach = 6.0;    // pixels: how far from a foam particle its foam reaches
  double foam_density = 6.0;  // particles' worth of foam, within a reach, that make a patch
  Color foam_color{1.0, 1.0, 1.0};
  bool bubbles = true;
  double bubble_size = 6.0;  // pixels across
  int max_bubbles = 12;      // a frame's most salient bubbles
};

struct RenderConfig {
  int width = 640;
  int height = 480;
  RenderQuality quality = RenderQuality::final;  // render_presets.hpp
  bool antialias = true;                         // false: off whatever the quality
  std::optional<FrameRange> frames;              // default: every frame found
  int fps = default_frame_rate;                  // frames per second of the animation's video
  Color background{0.93, 0.96, 1.0};
};

struct SceneConfig {
  CameraConfig camera;
  LightConfig light;
  WaterConfig water;
  OutlineConfig outline;
  FlowConfig flow;
  std::vector<ObjectConfig> objects;
  ParticlesConfig particles;
  RenderConfig render;
};

// Where the configuration comes from. `object_patterns` (from --object) are appended to the
// file's [[object]] list before the overrides apply, so `--set object.0.color=[1,0,0]` reaches
// them too. Overrides are "key=value" with a dotted key; the value is TOML (a bare word is
// taken as a string).
struct ConfigSources {
  std::optional<std::filesystem::path> file;
  std::vector<std::string> object_patterns;
  std::vector<std::string> overrides;
};

SceneConfig load_config(const ConfigSources& sources);

// One key of scene.toml as the schema defines it, for documentation and its checks.
struct ConfigKey {
  std::string key;            // "water.ior"; an object's keys as "object.name"
  std::string type;           // "number from 1 to 3", "colour [r, g, b] in 0-1", ...
  std::string default_value;  // as documented: 1.33, [1,1,1], "toon", or what decides it
  std::string help;           // one line
};

// Every key, section by section in the order of the documentation.
std::vector<ConfigKey> config_keys();

// Parses "A-B" or "A" (frame numbers, A <= B). Throws ConfigError naming `key`.
FrameRange parse_frame_range(const std::string& text, const std::string& key);

// Reduces text to a POV-Ray identifier fragment: ASCII letters, digits and '_' kept, anything
// else replaced by '_', at most 24 characters, never empty.
std::string sanitize_identifier(const std::string& text);

}  // namespace toonwater
