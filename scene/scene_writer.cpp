#include "scene/scene_writer.hpp"

#include "scene/pov_numbers.hpp"

#include "analyzer/colormap.hpp"

#include "scene/axes.hpp"
#include "scene/toon_template.hpp"
#include "scene/seen_through_water.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace toonwater {
namespace {

std::string num(double v) {
  std::string s;
  append_pov_number(s, v);
  return s;
}

// Built with += only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
std::string triple(std::string s, double a, double b, double c) {
  s += '<';
  s += num(a);
  s += ", ";
  s += num(b);
  s += ", ";
  s += num(c);
  s += '>';
  return s;
}

std::string vec(const Vec3& v) { return triple("", v.x(), v.y(), v.z()); }
// Colours in the config are as a person picks them on screen (sRGB); `srgb` makes POV-Ray turn
// them into the linear values it computes with (assumed_gamma 1.0), and the PNG it writes is
// sRGB again, so a flat band shows exactly the configured colour.
std::string rgb(const Color& c) { return triple("srgb ", c[0], c[1], c[2]); }
// A colour computed in POV-Ray's linear values (seen_through_water.hpp), possibly outside [0, 1].
std::string linear_rgb(const Color& c) { return triple("rgb ", c[0], c[1], c[2]); }

Color times(const Color& a, const Color& b) { return {a[0] * b[0], a[1] * b[1], a[2] * b[2]}; }

// A string literal for POV-Ray: only names this program built from sanitised identifiers reach
// it, but quotes and backslashes are escaped all the same.
std::string quoted(const std::string& s) {
  std::string out(1, '"');
  for (char c : s) {
    if (c == '"' || c == '\\') out += '\\';
    out += c;
  }
  return out + "\"";
}

std::string padded(long frame, int digits) {
  std::string s = std::to_string(frame);
  if (s.size() < static_cast<std::size_t>(digits)) s.insert(0, digits - s.size(), '0');
  return s;
}

std::string mesh_id(const std::string& name) {
  return std::string("Obj_").append(name).append("_mesh");
}
std::string shell_id(const std::string& name) {
  return std::string("Obj_").append(name).append("_shell");
}

void camera(std::string& s, const SceneLayout& l) {
  const CameraPlacement& c = l.camera;
  s += "camera {\n  perspective\n  location " + vec(c.location) + "\n  look_at " + vec(c.look_at) +
       "\n  right x * image_width / image_height\n  angle " + num(c.angle) + "\n}\n\n";
}

// The default view: from the front (−z) and 30° above, looking down at the scene.
const Vec3 kViewDirection = Vec3(0.0, -0.5, 0.8660254);
// Share of the picture's half-width and half-height the framed box may take.
constexpr double kFrameFill = 0.92;

// The diverging colour map of the curvature maps (analyzer/colormap.hpp) as a POV-Ray
// colour map over u in [0, 1]: u = 0.5 + 0.4999 t for t in [−1, 1], sampled every 0.1 in t.
std::string curvature_view_pigment() {
  std::string s = "pigment { uv_mapping gradient x color_map {";
  for (int step = -10; step <= 10; ++step) {
    const double t = step / 10.0;
    const Rgb8 c = diverging_colour(t);
    s += "\n      [" + num(0.5 + 0.4999 * t) + " color " +
         rgb({c[0] / 255.0, c[1] / 255.0, c[2] / 255.0}) + "]";
  }
  return s + " } }";
}

std::string flat_finish() { return "finish { emission 1 diffuse 0 ambient 0 }"; }

// The flat shading of water and objects (Toon_flat_shading): ka, kd and the light's colour.
std::string flat_shading(const SceneConfig& c) {
  return "finish { Toon_flat_shading(" + num(c.water.ka) + ", <1, 1, 1>, " + num(c.water.kd) +
         ", " + vec({c.light.color[0], c.light.color[1], c.light.color[2]}) + ")";
}

std::string finish(const SceneConfig& c, bool water) {
  const WaterConfig& w = c.water;
  std::string s = flat_shading(c);
  if (w.ks > 0) s += " phong " + num(w.ks) + " phong_size " + num(w.phong_size);
  if (water && w.reflection > 0) s += " reflection { " + num(w.reflection) + " }";
  return s + " }";
}

}  // namespace

LightGeometry light_geometry(const LightConfig& light, Axis up) {
  LightGeometry g;
  if (light.position) {
    g.parallel = false;
    g.vector = to_povray(*light.position, up);
  } else if (light.direction) {
    g.vector = to_povray(light.direction->normalized(), up);
  } else {
    g.vector = Vec3(-0.45, 1.0, -0.55).normalized();
  }
  return g;
}

CameraPlacement frame_camera(const SceneConfig& config, Axis up, const Vec3& scene_min,
                             const Vec3& scene_max) {
  const CameraConfig& c = config.camera;
  CameraPlacement out;
  out.angle = c.angle;
  const Vec3 centre = 0.5 * (scene_min + scene_max);
  out.look_at = c.look_at ? to_povray(*c.look_at, up) : centre;
  if (c.location) {
    out.location = to_povray(*c.location, up);
    return out;
  }
  // Fits the box's corners into the picture: the look-at point (unless configured) moves in the
  // picture plane to centre them, the distance scales them to the frame; a few rounds converge.
  const Vec3 d = kViewDirection.normalized();
  const Vec3 right = Vec3::UnitY().cross(d).normalized();
  const Vec3 upward = d.cross(right);
  const double tan_x = std::tan(0.5 * c.angle * std::numbers::pi / 180.0);
  const double tan_y = tan_x * config.render.height / config.render.width;
  const double radius = std::max(0.5 * (scene_max - scene_min).norm(), 1e-9);
  double distance = radius / std::sin(std::atan(std::min(tan_x, tan_y)));
  Vec3 target = out.look_at;
  for (int round = 0; round < 60; ++round) {
    const Vec3 eye = target - distance * d;
    double lo_x = 1e300, hi_x = -1e300, lo_y = 1e300, hi_y = -1e300;
    bool behind = false;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p((corner & 1 ? scene_max : scene_min).x(),
                   (corner & 2 ? scene_max : scene_min).y(),
                   (corner & 4 ? scene_max : scene_min).z());
      const double depth = (p - eye).dot(d);
      if (depth < 0.05 * radius) behind = true;
      const double x = (p - eye).dot(right) / depth, y = (p - eye).dot(upward) / depth;
      lo_x = std::min(lo_x, x), hi_x = std::max(hi_x, x);
      lo_y = std::min(lo_y, y), hi_y = std::max(hi_y, y);
    }
    if (behind) {
      distance *= 1.5;
      continue;
    }
    if (!c.look_at)
      target += distance * (0.5 * (lo_x + hi_x) * right + 0.5 * (lo_y + hi_y) * upward);
    const double scale =
        std::max((hi_x - lo_x) / tan_x, (hi_y - lo_y) / tan_y) / (2.0 * kFrameFill);
    distance *= std::clamp(scale, 0.5, 2.0);
  }
  out.look_at = target;
  out.location = target - distance * d;
  return out;
}

std::vector<double> pixel_widths(const SceneMesh& mesh, const CameraPlacement& camera,
                                 int image_width) {
  // A pixel at depth z (along the view axis) spans 2 z tan(angle / 2) / width.
  const Vec3 d = (camera.look_at - camera.location).normalized();
  const double per_depth =
      2.0 * std::tan(0.5 * camera.angle * std::numbers::pi / 180.0) / std::max(1, image_width);
  const double nearest = 1e-6 * std::max(mesh.diagonal(), 1e-9);
  std::vector<double> widths(mesh.positions.size());
  for (std::size_t v = 0; v < widths.size(); ++v)
    widths[v] = per_depth * std::max((mesh.positions[v] - camera.location).dot(d), nearest);
  return widths;
}

std::vector<double> shell_offsets(const OutlineConfig& outline, const SceneMesh& mesh,
                                  const CameraPlacement& camera, int image_width) {
  const std::size_t n = mesh.positions.size();
  switch (outline.units) {
    case WidthUnits::world:
      return std::vector<double>(n, outline.width.value_or(0.01));
    case WidthUnits::relative:
      return std::vector<double>(n, outline.width.value_or(0.006) * mesh.diagonal());
    case WidthUnits::pixels:
      break;
  }
  std::vector<double> offsets = pixel_widths(mesh, camera, image_width);
  for (double& offset : offsets) offset *= outline.width.value_or(kDefaultOutlinePixels);
  return offsets;
}

double calm_light(const SceneLayout& l) {
  const LightGeometry g = light_geometry(l.config->light, l.up);
  if (g.parallel) return g.vector.y();
  const Vec3 top((l.water_min.x() + l.water_max.x()) / 2, l.water_max.y(),
                 (l.water_min.z() + l.water_max.z()) / 2);
  const Vec3 to_light = g.vector - top;
  return to_light.norm() > 0 ? to_light.normalized().y() : 1.0;
}

std::pair<double, double> water_thresholds(const SceneLayout& l) {
  const WaterConfig& w = l.config->water;
  if (w.bands == BandThresholds::absolute) return {w.t_bright, w.t_medium};
  // Kept inside (−1, 1), where the band keys stay inside the colour map.
  const double calm = calm_light(l);
  const double margin = w.bands_above_noise ? band_noise_multiple * l.normal_noise *
                                                  std::sqrt(std::max(0.0, 1.0 - calm * calm))
                                            : 0.0;
  return {std::clamp(calm + std::max(w.dt_bright, margin), -0.999, 0.999),
          std::clamp(calm + std::min(w.dt_medium, -margin), -0.9995, 0.9985)};
}

std::string water_line_id(const std::string& object_name) {
  return std::string("Obj_").append(object_name).append("_water_line");
}

std::string object_water_id(const std::string& object_name) {
  return std::string("Obj_").append(object_name).append("_water");
}

std::string object_contact_id(const std::string& object_name) {
  return std::string("Obj_").append(object_name).append("_contact");
}

std::string object_water_declaration(const std::string& object_name, const SceneMesh* closed_water,
                                     double line_height, double contact) {
  std::string s = "#declare " + water_line_id(object_name) + " = " + num(line_height) + ";\n";
  s += "#declare " + object_water_id(object_name) + " = ";
  // The closed mesh inside a box around it: POV-Ray refuses a textured object (the water's
  // faces carry their textures) in an object pattern, but not CSG holding one.
  if (closed_water) {
    const Vec3 margin = Vec3::Constant(0.01 * closed_water->diagonal() + 1e-6);
    s += "intersection { object { Water_mesh } box { " + vec(closed_water->min - margin) + ", " +
         vec(closed_water->max + margin) + " } }\n";
  } else {
    s += "plane { y, " + num(line_height) + " }\n";
  }
  return s + "#declare " + object_contact_id(object_name) + " = " + num(contact) + ";\n";
}

CameraReach camera_reach(const SceneLayout& l, const Vec3& min, const Vec3& max) {
  // The camera is placed before any frame is written (frame_camera), so the nearest point of
  // the box is known exactly.
  CameraReach reach;
  reach.angle_degrees = l.camera.angle;
  reach.width = l.config->render.width;
  reach.height = l.config->render.height;
  const Vec3& eye = l.camera.location;
  reach.nearest_distance = (eye - eye.cwiseMax(min).cwiseMin(max)).norm();
  return reach;
}

std::string water_include_name(long frame) { return "water_" + padded(frame, 4) + ".inc"; }
std::string spray_include_name(long frame) { return "spray_" + padded(frame, 4) + ".inc"; }
std::string foam_include_name(long frame) { return "foam_" + padded(frame, 4) + ".inc"; }
std::string bubbles_include_name(long frame) { return "bubbles_" + padded(frame, 4) + ".inc"; }

std::string object_include_name(const std::string& name, bool animated, long frame) {
  std::string s = std::string("obj_").append(name);
  if (animated) s.append(".").append(padded(frame, 4));  // '.' is in no object name: no clash
  return s.append(".inc");
}

std::string frame_image_name(const SceneLayout& l, long frame) {
  if (!l.animation) return "frame.png";
  return "frame_" + padded(frame, static_cast<int>(std::to_string(l.last_frame).size())) + ".png";
}

bool draws_flow_regions(const SceneConfig& c) {
  return c.water.shading == WaterShading::toon && c.flow.enabled &&
         c.flow.style != FlowStyle::lines;
}

bool draws_flow_lines(const SceneConfig& c) {
  return c.water.shading == WaterShading::toon && c.flow.enabled &&
         c.flow.style != FlowStyle::regions;
}

ToonLimits water_toon_limits(const SceneLayout& l) {
  const auto [t_bright, t_medium] = water_thresholds(l);
  ToonLimits limits{{band_coordinate(t_medium), band_coordinate(t_bright)}, std::nullopt};
  if (draws_flow_regions(*l.config)) limits.flow = {flow_coordinate(-1.0), flow_coordinate(1.0)};
  return limits;
}

std::string scene_pov(const SceneLayout& l) {
  const SceneConfig& c = *l.config;
  const WaterConfig& w = c.water;
  const WaterSurfaceLook look = water_surface_look(c);
  const Color line_seen_through = line_seen_through_water(linear_from_srgb(c.outline.color), look);
  // A curvature view is opaque and flat: it shows the curvature, not the water's optics.
  const bool curvature_view = w.shading != WaterShading::toon;
  const bool refracts = !curvature_view && w.transmit > 0;
  const bool reflects = !curvature_view && w.reflection > 0;
  const bool closed_volume = l.closed_water && refracts;
  std::string s;
  s += "// Written by toonwater povgen. Render every frame with `povray scene.ini` here.\n";
  s += "#version 3.7;\n#include \"toon.inc\"\n\n";
  // Secondary rays need depth; a pixel whose rays run out of it turns black, the line colour
  // (povray-notes.md).
  const bool secondary_rays = reflects || refracts || c.outline.enabled;
  s += secondary_rays ? "global_settings { assumed_gamma 1.0 max_trace_level 10 }\n\n"
                      : "global_settings { assumed_gamma 1.0 }\n\n";
  const FlowConfig& flow = c.flow;
  const bool flow_regions = draws_flow_regions(c);
  const bool flow_lines = draws_flow_lines(c);
  if (flow_lines) {
    // Read by Toon_stroke while the water include is parsed: strokes as wide on screen near
    // and far.
    s += "// Flow lines: width in pixels, and what turns it into a radius at a distance\n";
    s += "#declare Toon_line_width = " + num(flow.line_width) + ";\n";
    s += "#declare Toon_camera_location = " + vec(l.camera.location) + ";\n";
    s += "#declare Toon_pixel_angle = 2 * tan(radians(" + num(l.camera.angle) +
         ") / 2) / image_width;\n\n";
  }

  const auto [t_bright, t_medium] = water_thresholds(l);
  const std::string bands = rgb(w.bright) + ", " + rgb(w.medium) + ", " + rgb(w.dark) + ", " +
                            num(t_bright) + ", " + num(t_medium);
  const std::string two_bands =
      rgb(w.bright) + ", " + rgb(w.dark) + ", " + num(t_bright) + ", " + num(t_medium);
  // What the bands pass of what lies behind them: kt, and less in the dark band
  // (seen_through_water.hpp).
  const std::string transmits = num(look.medium.transmit) + ", " + num(look.dark.transmit);
  // The bands (of three, or of two where dark meets bright: band_crossings.hpp) under the flow
  // regions, when they are drawn.
  auto water_pigment = [&](const std::string& band_pigment) {
    if (!flow_regions) return band_pigment;
    return "Toon_flow_over(" + band_pigment + ",\n    " + rgb(flow.valley_color) + ", " +
           rgb(flow.ridge_color) + ")";
  };
  if (!curvature_view) {
    const std::string surface_finish = finish(c, true);
    s += "// The water's textures: its own, and for faces where dark meets bright, two bands\n";
    s += std::string("#declare ") + kWaterSurfaceTexture + " = texture {\n  " +
         water_pigment("Toon_bands(" + bands + ", " + transmits + ")") + "\n  " + surface_finish +
         "\n}\n";
    s += std::string("#declare ") + kWaterSurfaceTwoBandTexture + " = texture {\n  " +
         water_pigment("Toon_two_bands(" + two_bands + ", " + transmits + ")") + "\n  " +
         surface_finish + "\n}\n";
    if (flow_regions) {
      s += "// Faces across a flow region's edge whose other corners lie in one band: that band\n";
      const std::array<Color, 3> colours{w.dark, w.medium, w.bright};
      const std::array<double, 3> passed{look.dark.transmit, look.medium.transmit,
                                         look.bright.transmit};
      for (std::size_t b = 0; b < colours.size(); ++b)
        s += std::string("#declare ") + kWaterOneBandTextures[b] + " = texture {\n  " +
             water_pigment("pigment { color " + rgb(colours[b]) + " transmit " + num(passed[b]) +
                           " }") +
             "\n  " + surface_finish + "\n}\n";
    }
    if (closed_volume) {
      // A closed volume is a see-through free surface over an opaque body: its walls and floor
      // show flat bands, and nothing is seen through them, so objects leave no ghost images on
      // the walls and no ray bounces around inside.
      const std::string body_finish = flat_shading(c) + " }";
      s += "// The closed volume's walls and floor: opaque\n";
      s += std::string("#declare ") + kWaterBodyTexture + " = texture {\n  Toon_bands(" + bands +
           ", 0, 0)\n  " + body_finish + "\n}\n";
      s += std::string("#declare ") + kWaterBodyTwoBandTexture + " = texture {\n  Toon_two_bands(" +
           two_bands + ", 0, 0)\n  " + body_finish + "\n}\n";
    }
    s += "\n";
  }
  if (l.foam) {
    // Foam paints the free surface's textures (not an opaque body's walls and floor), flat.
    s += "// Foam: the free surface painted where this frame's foam gathers (Foam_patches)\n";
    s += "#include concat(\"foam_\", str(frame_number, -4, 0), \".inc\")\n";
    s += "#ifdef (Foam_patches)\n";
    s += "  #declare Toon_foam = texture { pigment { color " + rgb(c.particles.foam_color) +
         " }\n    " + flat_shading(c) + " } }\n";
    std::vector<const char*> painted{kWaterSurfaceTexture, kWaterSurfaceTwoBandTexture};
    if (flow_regions)
      painted.insert(painted.end(), kWaterOneBandTextures.begin(), kWaterOneBandTextures.end());
    for (const char* id : painted)
      s += std::string("  #declare ") + id + " = Toon_foam_over(" + id +
           ", Foam_patches, Toon_foam)\n";
    s += "#end\n\n";
  }
  if (l.spray) {
    // Read by Toon_droplet while the spray include is parsed.
    s += "// Spray droplets: the water's bands at the objects' thresholds, outlined\n";
    s += "#declare Toon_droplet_colors = array[3] { " + rgb(w.bright) + ", " + rgb(w.medium) +
         ", " + rgb(w.dark) + " }\n";
    s += "#declare Toon_droplet_thresholds = <" + num(w.t_bright) + ", " + num(w.t_medium) + ">;\n";
    s += "#declare Toon_droplet_finish = " + finish(c, false) + "\n";
    s += "#declare Toon_droplet_line_color = " + rgb(c.outline.color) + ";\n\n";
  }
  if (l.bubbles) {
    // Read by Toon_bubble while the bubbles include is parsed. A bubble shows the water's
    // bright colour under calm water, outlined like an object under water.
    s += "// Bubbles: discs in the water's bright colour and the line colour, as seen through "
         "its surface\n";
    s += "#declare Toon_bubble_color = " +
         linear_rgb(seen_through_water(linear_from_srgb(w.bright), {1, 1, 1}, look.medium, look)) +
         ";\n";
    s += "#declare Toon_bubble_line_color = " + linear_rgb(line_seen_through) + ";\n";
    s += "#declare Toon_bubble_ior = " + num(w.ior) + ";\n\n";
  }
  s += "// Meshes of the current frame\n";
  s += "#include concat(\"water_\", str(frame_number, -4, 0), \".inc\")\n";
  for (const ObjectPlacement& o : l.objects) {
    if (o.animated)
      s += "#include concat(" + quoted("obj_" + o.config->name + ".") +
           ", str(frame_number, -4, 0), \".inc\")\n";
    else
      s += "#include " + quoted(object_include_name(o.config->name, false, 0)) + "\n";
  }
  if (l.spray) s += "#include concat(\"spray_\", str(frame_number, -4, 0), \".inc\")\n";
  if (l.bubbles) s += "#include concat(\"bubbles_\", str(frame_number, -4, 0), \".inc\")\n";
  s += "\n";
  camera(s, l);

  // The light only makes highlights: diffuse is 0, the bands come from the u coordinate.
  const Vec3 centre = 0.5 * (l.water_min + l.water_max);
  const double size = std::max((l.water_max - l.water_min).norm(), 1e-6);
  if (w.ks > 0) {
    const LightGeometry g = light_geometry(c.light, l.up);
    const Color colour = times(c.light.color, w.specular_color);  // Id * Os
    if (g.parallel) {
      const double far = 10.0 * size;
      s += "light_source { " + vec(centre + far * g.vector) + " color " + rgb(colour) +
           " parallel point_at " + vec(centre) + " shadowless }\n";
    } else {
      s += "light_source { " + vec(g.vector) + " color " + rgb(colour) + " shadowless }\n";
    }
  }
  s += "background { color " + rgb(c.render.background) + " }\n\n";
  if (reflects) {
    // A flat sky for reflected rays that miss every object (no_image: the camera does not
    // see it), so that a reflection reads as the object against the water's own colour.
    const Vec3 sky_centre = 0.5 * (l.camera.location + centre);
    const double sky_radius = 1000.0 * (size + (l.camera.location - centre).norm());
    s += "// Sky seen in reflections only\nsphere { " + vec(sky_centre) + ", " + num(sky_radius) +
         "\n  texture { pigment { color " + rgb(w.sky.value_or(w.bright)) + " } " + flat_finish() +
         " }\n  hollow no_image no_shadow\n}\n\n";
  }

  if (curvature_view) {
    s += "// Water coloured by its " +
         std::string(w.shading == WaterShading::gaussian ? "Gaussian" : "mean") +
         " curvature: u = 0.5 + 0.4999 * value / range, the curvature maps' colours\n";
  } else {
    s += "// Water: Cartoon Water Shader\n";
  }
  s += "object {\n  Water_mesh\n  texture {\n    ";
  s += curvature_view ? curvature_view_pigment() + "\n    " + flat_finish()
                      : std::string(kWaterSurfaceTexture);
  s += "\n  }\n";
  if (refracts) s += "  interior { ior " + num(w.ior) + " }\n";
  s += "}\n";
  if (flow_lines) {
    // Strokes lie on the water, half above it: the water must not reflect them a second time.
    const bool both = flow.style == FlowStyle::regions_and_lines;
    const Color ridge = flow.line_color.value_or(both ? c.outline.color : flow.ridge_color);
    const Color valley = flow.line_color.value_or(both ? c.outline.color : flow.valley_color);
    for (const auto& [id, colour] :
         {std::pair{"Water_ridge_lines", ridge}, std::pair{"Water_valley_lines", valley}})
      s += std::string("#ifdef (") + id + ")\n  object { " + id + " texture { pigment { color " +
           rgb(colour) + " } finish { emission 1 diffuse 0 ambient 0 } } no_shadow" +
           (reflects ? " no_reflection" : "") + " }\n#end\n";
  }
  // The water's shell lies above its surface: rays the water reflects would meet its inside.
  if (c.outline.enabled)
    s += "object { Toon_outline_shell(Water_shell, " + rgb(c.outline.color) + ")" +
         (reflects ? " no_reflection }\n" : " }\n");

  if (l.spray) s += "object { Spray_droplets }\n";

  // Under the water: colours that show through its surface as a cartoon draws them.
  const Color& gain = look.gain;
  if (l.bubbles) s += "object { Water_bubbles }\n";
  for (const ObjectPlacement& o : l.objects) {
    const ObjectConfig& oc = *o.config;
    const bool outline = c.outline.enabled && oc.outline;
    const bool hidden_in_water = reflects && oc.reflection != ReflectionTarget::concrete;
    const bool in_water = refracts && o.submerged;
    const std::string in_air = "Toon_object_bands(" + rgb(oc.color) + ", " + num(w.t_bright) +
                               ", " + num(w.t_medium) + ")\n    " + finish(c, false);
    s += "\n// Object " + oc.name + "\nobject {\n  " + mesh_id(oc.name) + "\n  texture {\n    ";
    if (in_water) {
      // The object's three bands (Toon_object_bands), tinted, as they show through the water.
      const Color tint = linear_from_srgb(submerged_tint(oc.color, w.medium));
      std::string under = "Toon_bands(";
      for (const double share : {1.0, 0.6, 0.3}) {
        const Color band{share * tint[0] * gain[0], share * tint[1] * gain[1],
                         share * tint[2] * gain[2]};
        under += linear_rgb(seen_through_water(band, gain, look.medium, look)) + ", ";
      }
      under += num(w.t_bright) + ", " + num(w.t_medium) + ", 0, 0)\n    " + finish(c, false);
      s += "Toon_in_water(" + object_water_id(oc.name) + ", " + object_contact_id(oc.name) +
           ",\n    texture { " + in_air + " },\n    texture { " + under +
           " },\n    texture { pigment { color " + rgb(c.outline.color) + " } " + flat_finish() +
           " },\n    texture { pigment { color " + linear_rgb(line_seen_through) + " } " +
           flat_finish() + " })\n  }\n";
    } else {
      s += in_air + "\n  }\n";
    }
    if (hidden_in_water) s += "  no_reflection\n";
    s += "}\n";
    if (outline) {
      const std::string shell = "object { Toon_outline_shell(" + shell_id(oc.name) + ", ";
      const std::string tail =
          reflects && oc.reflection == ReflectionTarget::none ? " no_reflection }\n" : " }\n";
      if (in_water) {
        const std::string line = water_line_id(oc.name);
        s += shell + rgb(c.outline.color) + ") clipped_by { plane { -y, -" + line + " } }" + tail;
        s += shell + linear_rgb(line_seen_through) + ") clipped_by { plane { y, " + line +
             " } } interior { ior " + num(w.ior) + " }" + tail;
      } else {
        s += shell + rgb(c.outline.color) + ")" + tail;
      }
    } else if (reflects && oc.reflection == ReflectionTarget::abstract) {
      s += "object { Toon_silhouette(" + mesh_id(oc.name) + ", " + rgb(c.outline.color) + ") }\n";
    }
  }
  return s;
}

std::string scene_toon_inc(const SceneLayout& l) {
  const SceneConfig& c = *l.config;
  const bool reflects = c.water.shading == WaterShading::toon && c.water.reflection > 0;
  std::vector<std::string> parts{"bands"};
  if (draws_flow_regions(c)) parts.push_back("flow");
  if (draws_flow_lines(c)) parts.push_back("strokes");
  if (!l.objects.empty()) parts.push_back("objects");
  if (c.outline.enabled || l.spray || l.bubbles)
    parts.push_back("outline");  // droplets' and bubbles' shells too
  if (l.spray) parts.push_back("droplets");
  if (l.foam) parts.push_back("foam");
  if (l.bubbles) parts.push_back("bubbles");
  for (const ObjectPlacement& o : l.objects)
    if (reflects && !(c.outline.enabled && o.config->outline) &&
        o.config->reflection == ReflectionTarget::abstract) {
      parts.push_back("silhouette");
      break;
    }
  return toon_template_parts(parts);
}

std::string scene_ini(const SceneLayout& l) {
  const RenderConfig& r = l.config->render;
  std::string s = "; Written by toonwater povgen. Run `povray scene.ini` in this directory.\n";
  s += "Input_File_Name=\"scene.pov\"\n";
  s += l.animation ? "Output_File_Name=\"frame_\"\n" : "Output_File_Name=\"frame.png\"\n";
  s += "Output_File_Type=N\n";
  const RenderPreset& preset = render_preset(r.quality);
  s += "Width=" + std::to_string(std::max(1, r.width / preset.divisor)) +
       "\nHeight=" + std::to_string(std::max(1, r.height / preset.divisor)) + "\n";
  if (r.antialias && preset.antialias_threshold)
    s += "Antialias=On\nAntialias_Threshold=" + num(*preset.antialias_threshold) +
         "\nAntialias_Depth=" + std::to_string(preset.antialias_depth) + "\n";
  else
    s += "Antialias=Off\n";
  s += "Display=Off\nPause_When_Done=Off\n";
  if (l.animation)
    s += "Initial_Frame=" + std::to_string(l.first_frame) +
         "\nFinal_Frame=" + std::to_string(l.last_frame) +
         "\n; Frames per second of `toonwater render --video` (render.fps); POV-Ray has no such "
         "option.\n; Frame_Rate=" +
         std::to_string(r.fps) + "\n";
  return s;
}

}  // namespace toonwater
