#include "povgen/scene_writer.hpp"

#include "analyzer/maps/colormap.hpp"

#include "povgen/axes.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace toonwater::povgen {
namespace {

std::string num(double v) {
  if (!std::isfinite(v)) throw std::logic_error("scene writer: non-finite number");
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 7);
  return std::string(buf, r.ptr);
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

std::string mesh_id(const std::string& name) { return std::string("Obj_").append(name).append("_mesh"); }
std::string shell_id(const std::string& name) { return std::string("Obj_").append(name).append("_shell"); }

Vec3 camera_look_at(const SceneLayout& l) {
  const CameraConfig& c = l.config->camera;
  return c.look_at ? to_povray(*c.look_at, l.up) : Vec3(0.5 * (l.water_min + l.water_max));
}

Vec3 camera_location(const SceneLayout& l) {
  const CameraConfig& c = l.config->camera;
  if (c.location) return to_povray(*c.location, l.up);
  // Framed on the bounding sphere, from the front (−z) and 30° above.
  const double radius = std::max(0.5 * (l.water_max - l.water_min).norm(), 1e-9);
  const double aspect = static_cast<double>(l.config->render.height) / l.config->render.width;
  const double half_h = 0.5 * c.angle * std::numbers::pi / 180.0;
  const double half = std::min(half_h, std::atan(std::tan(half_h) * aspect));
  return camera_look_at(l) + radius / std::sin(half) * Vec3(0.0, 0.5, -0.8660254);
}

void camera(std::string& s, const SceneLayout& l) {
  s += "camera {\n  perspective\n  location " + vec(camera_location(l)) + "\n  look_at " +
       vec(camera_look_at(l)) + "\n  right x * image_width / image_height\n  angle " +
       num(l.config->camera.angle) + "\n}\n\n";
}

// The diverging colour map of the curvature maps (analyzer/maps/colormap.hpp) as a POV-Ray
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

std::string finish(const SceneConfig& c, bool water) {
  const WaterConfig& w = c.water;
  std::string s = "finish { Toon_flat_shading(" + num(w.ka) + ", <1, 1, 1>, " + num(w.kd) +
                  ", " + vec({c.light.color[0], c.light.color[1], c.light.color[2]}) + ")";
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

CameraReach camera_reach(const SceneLayout& l, const Vec3& min, const Vec3& max) {
  const SceneConfig& c = *l.config;
  CameraReach reach;
  reach.angle_degrees = c.camera.angle;
  reach.width = c.render.width;
  reach.height = c.render.height;
  if (c.camera.location) {
    const Vec3 eye = to_povray(*c.camera.location, l.up);
    reach.nearest_distance = (eye - eye.cwiseMax(min).cwiseMin(max)).norm();
  } else {
    // The default camera frames a sphere holding every frame's box at distance R / sin(half),
    // half the field of view across the image's shorter side (camera_location): no point of
    // the sphere is nearer than R (1 / sin(half) − 1), and R is at least this box's radius.
    const double aspect = static_cast<double>(c.render.height) / c.render.width;
    const double half_h = 0.5 * c.camera.angle * std::numbers::pi / 180.0;
    const double half = std::min(half_h, std::atan(std::tan(half_h) * aspect));
    reach.nearest_distance = 0.5 * (max - min).norm() * (1.0 / std::sin(half) - 1.0);
  }
  return reach;
}

std::string water_include_name(long frame) { return "water_" + padded(frame, 4) + ".inc"; }

std::string object_include_name(const std::string& name, bool animated, long frame) {
  std::string s = std::string("obj_").append(name);
  if (animated) s.append("_").append(padded(frame, 4));
  return s.append(".inc");
}

std::string frame_image_name(const SceneLayout& l, long frame) {
  if (!l.animation) return "frame.png";
  return "frame_" + padded(frame, static_cast<int>(std::to_string(l.last_frame).size())) + ".png";
}

std::string scene_pov(const SceneLayout& l) {
  const SceneConfig& c = *l.config;
  const WaterConfig& w = c.water;
  // A curvature view is opaque and flat: it shows the curvature, not the water's optics.
  const bool curvature_view = w.shading != WaterShading::toon;
  const bool refracts = !curvature_view && w.transmit > 0;
  const bool reflects = !curvature_view && w.reflection > 0;
  std::string s;
  s += "// Written by toonwater povgen. Render every frame with `povray scene.ini` here.\n";
  s += "#version 3.7;\n#include \"toon.inc\"\n\n";
  // Reflected, refracted and shell-crossing rays need depth; a pixel whose rays run out of it
  // turns black, the line colour (povray-notes.md).
  const bool secondary_rays = reflects || refracts || c.outline.enabled;
  s += secondary_rays ? "global_settings { assumed_gamma 1.0 max_trace_level 10 }\n\n"
                      : "global_settings { assumed_gamma 1.0 }\n\n";
  const FlowConfig& flow = c.flow;
  const bool flow_regions = !curvature_view && flow.enabled && flow.style != FlowStyle::lines;
  const bool flow_lines = !curvature_view && flow.enabled && flow.style != FlowStyle::regions;
  if (flow_lines) {
    // Read by Toon_stroke while the water include is parsed: strokes as wide on screen near
    // and far.
    s += "// Flow lines: width in pixels, and what turns it into a radius at a distance\n";
    s += "#declare Toon_line_width = " + num(flow.line_width) + ";\n";
    s += "#declare Toon_camera_location = " + vec(camera_location(l)) + ";\n";
    s += "#declare Toon_pixel_angle = 2 * tan(radians(" + num(c.camera.angle) +
         ") / 2) / image_width;\n\n";
  }
  s += "// Meshes of the current frame\n";
  s += "#include concat(\"water_\", str(frame_number, -4, 0), \".inc\")\n";
  for (const ObjectPlacement& o : l.objects) {
    if (o.animated)
      s += "#include concat(" + quoted("obj_" + o.config->name + "_") +
           ", str(frame_number, -4, 0), \".inc\")\n";
    else
      s += "#include " + quoted(object_include_name(o.config->name, false, 0)) + "\n";
  }
  s += "\n";
  camera(s, l);

  // The light only makes highlights: diffuse is 0, the bands come from the u coordinate.
  if (w.ks > 0) {
    const LightGeometry g = light_geometry(c.light, l.up);
    const Color colour = times(c.light.color, w.specular_color);  // Id * Os
    if (g.parallel) {
      const Vec3 centre = 0.5 * (l.water_min + l.water_max);
      const double far = 10.0 * std::max((l.water_max - l.water_min).norm(), 1e-6);
      s += "light_source { " + vec(centre + far * g.vector) + " color " + rgb(colour) +
           " parallel point_at " + vec(centre) + " shadowless }\n";
    } else {
      s += "light_source { " + vec(g.vector) + " color " + rgb(colour) + " shadowless }\n";
    }
  }
  s += "background { color " + rgb(c.render.background) + " }\n\n";

  if (curvature_view) {
    s += "// Water coloured by its " +
         std::string(w.shading == WaterShading::gaussian ? "Gaussian" : "mean") +
         " curvature: u = 0.5 + 0.4999 * value / range, the curvature maps' colours\n";
    s += "object {\n  Water_mesh\n  texture {\n    " + curvature_view_pigment() +
         "\n    finish { emission 1 diffuse 0 ambient 0 }\n  }\n";
  } else {
    s += "// Water: Cartoon Water Shader\nobject {\n  Water_mesh\n  texture {\n    ";
    const std::string bands = rgb(w.bright) + ", " + rgb(w.medium) + ", " + rgb(w.dark) + ", " +
                              num(w.t_bright) + ", " + num(w.t_medium);
    if (flow_regions)
      s += "Toon_bands_with_flow(" + bands + ",\n      " + rgb(flow.valley_color) + ", " +
           rgb(flow.ridge_color) + ", " + num(w.transmit) + ")";
    else
      s += "Toon_bands(" + bands + ", " + num(w.transmit) + ")";
    s += "\n    " + finish(c, true) + "\n  }\n";
  }
  if (refracts) s += "  interior { ior " + num(w.ior) + " }\n";
  s += "}\n";
  if (flow_lines) {
    // Strokes lie on the water, half above it: the water must not reflect them a second time.
    const bool both = flow.style == FlowStyle::regions_and_lines;
    const Color ridge = flow.line_color.value_or(both ? c.outline.color : flow.ridge_color);
    const Color valley = flow.line_color.value_or(both ? c.outline.color : flow.valley_color);
    for (const auto& [id, colour] : {std::pair{"Water_ridge_lines", ridge}, std::pair{"Water_valley_lines", valley}})
      s += std::string("#ifdef (") + id + ")\n  object { " + id + " texture { pigment { color " +
           rgb(colour) + " } finish { emission 1 diffuse 0 ambient 0 } } no_shadow" +
           (reflects ? " no_reflection" : "") + " }\n#end\n";
  }
  // The water's shell lies above its surface: rays the water reflects would meet its inside.
  if (c.outline.enabled)
    s += "object { Toon_outline_shell(Water_shell, " + rgb(c.outline.color) + ")" +
         (reflects ? " no_reflection }\n" : " }\n");

  for (const ObjectPlacement& o : l.objects) {
    const ObjectConfig& oc = *o.config;
    const bool outline = c.outline.enabled && oc.outline;
    const bool hidden_in_water = reflects && oc.reflection != ReflectionTarget::concrete;
    s += "\n// Object " + oc.name + "\nobject {\n  " + mesh_id(oc.name) +
         "\n  texture {\n    Toon_object_bands(" + rgb(oc.color) + ", " + num(w.t_bright) + ", " +
         num(w.t_medium) + ")\n    " + finish(c, false) + "\n  }\n";
    if (hidden_in_water) s += "  no_reflection\n";
    s += "}\n";
    if (outline) {
      s += "object { Toon_outline_shell(" + shell_id(oc.name) + ", " + rgb(c.outline.color) + ")";
      if (refracts && o.submerged) s += " interior { ior " + num(w.ior) + " }";
      if (reflects && oc.reflection == ReflectionTarget::none) s += " no_reflection";
      s += " }\n";
    } else if (reflects && oc.reflection == ReflectionTarget::abstract) {
      s += "object { Toon_silhouette(" + mesh_id(oc.name) + ", " + rgb(c.outline.color) + ") }\n";
    }
  }
  return s;
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
         "\nFinal_Frame=" + std::to_string(l.last_frame) + "\n";
  return s;
}

}  // namespace toonwater::povgen
