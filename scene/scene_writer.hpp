// scene.pov and scene.ini: the parts of a toonwater scene that are the same for every frame.
// scene.pov includes templates/toon.inc and, per frame, the mesh2 includes the frame writer
// produced (water_NNNN.inc, obj_NAME.inc or obj_NAME.NNNN.inc). It contains only what the
// configuration needs: no light without highlights, no reflection finish or reflection targets
// when the water does not reflect, no interior when nothing refracts, no shells without
// outlines, no flow pigment without flow regions, no object code without objects.
//
// Everything written comes from validated values: finite numbers, known keywords and
// identifiers the configuration sanitised.
#pragma once

#include "scene/config.hpp"
#include "scene/scene_mesh.hpp"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace toonwater {

struct ObjectPlacement {
  const ObjectConfig* config = nullptr;
  bool animated = false;  // one mesh per frame
  // Below its water line in some frame. Then, when the water refracts, the object is drawn
  // apart in the frame's water and out of it (object_water_declaration): its texture in the
  // water tinted as seen through the surface, with a contact line along the surface
  // (seen_through_water.hpp, Toon_in_water), and its shell as two copies cut at the water
  // line: the part under it with the water's ior (else the shell's inside acts as an air
  // bubble) and a line colour seen through the surface, the part above without (else the rim
  // rays bend back onto the object).
  bool submerged = false;
};

// The camera in POV-Ray's frame; `angle` is the horizontal field of view in degrees.
struct CameraPlacement {
  Vec3 location = Vec3(0, 0, -1), look_at = Vec3::Zero();
  double angle = 40;
};

struct SceneLayout {
  const SceneConfig* config = nullptr;
  Axis up = Axis::y;
  Vec3 water_min = Vec3::Zero(), water_max = Vec3::Zero();  // POV-Ray frame, all frames
  CameraPlacement camera;
  std::vector<ObjectPlacement> objects;
  // Some frame's water is a closed volume and the water refracts: its faces carry per-face
  // textures declared in scene.pov (closed_volume_textures).
  bool closed_water = false;
  bool animation = false;  // false: one frame, written as frame 0
  // The noise floor of the water's shading normals, horizontal part (flow_regions.hpp): the
  // median over the frames the survey saw, or the first frame's; 0 when unknown.
  double normal_noise = 0.0;
  long first_frame = 0, last_frame = 0;
  bool spray = false;    // each frame's spray droplets, in spray_NNNN.inc (droplet_writer.hpp)
  bool foam = false;     // each frame's foam patches, in foam_NNNN.inc (foam_writer.hpp)
  bool bubbles = false;  // each frame's bubbles, in bubbles_NNNN.inc (bubble_writer.hpp)
};

// The camera: the configured location and look_at; what is not configured frames the box
// [scene_min, scene_max] (POV-Ray frame: water and objects of every frame): seen from the
// front and 30° above, the box's corners fill the picture up to a margin of 4 % on each side.
CameraPlacement frame_camera(const SceneConfig& config, Axis up, const Vec3& scene_min,
                             const Vec3& scene_max);

// The width of a pixel (of an image `image_width` wide) at each vertex's depth from the camera,
// in world units.
std::vector<double> pixel_widths(const SceneMesh& mesh, const CameraPlacement& camera,
                                 int image_width);

// The shell offset of each vertex of `mesh` for the configured outline width: in pixels, the
// width times the size of a pixel (of render.width) at the vertex's depth from the camera.
std::vector<double> shell_offsets(const OutlineConfig& outline, const SceneMesh& mesh,
                                  const CameraPlacement& camera, int image_width);

// The calm water's L·n: the light against the up axis (a point light: seen from the centre of
// the water's top), where relative band thresholds are measured from.
double calm_light(const SceneLayout& layout);

// The water's absolute band thresholds {T_bright, T_medium}. Relative ones are calm + dt, and
// unless dt_bright or dt_medium is given they keep 3 noise floors of L·n from calm, so that
// the simulation's normal noise on calm water never crosses a band limit: the noise floor of
// L·n is that of the normals' horizontal part times the light's horizontal part.
constexpr double band_noise_multiple = 3.0;
std::pair<double, double> water_thresholds(const SceneLayout& layout);

// An object's water in a frame, declared in the frame's water include when the water refracts:
// Obj_NAME_water_line, the height of the water's surface around the object (water_line in
// frame_include.hpp), where its shell is cut in two; Obj_NAME_water, an object whose
// inside is the water around the object (the frame's `closed_water` mesh, Water_mesh, else the
// half-space under the water line), where its texture changes; and Obj_NAME_contact, how deep the
// contact line reaches on each side of the water's surface (scene units; 0: none).
std::string water_line_id(const std::string& object_name);
std::string object_water_id(const std::string& object_name);
std::string object_contact_id(const std::string& object_name);
std::string object_water_declaration(const std::string& object_name, const SceneMesh* closed_water,
                                     double line_height, double contact);

// Texture identifiers of the water's faces (toon shading): the water's own, which a closed
// volume's free surface has, the opaque walls and floor of a closed volume, each one's two
// bands for faces where dark meets bright, and, where flow regions are drawn, one band alone
// for faces across a region's edge (band_crossings.hpp).
inline constexpr const char* kWaterSurfaceTexture = "Water_surface_texture";
inline constexpr const char* kWaterSurfaceTwoBandTexture = "Water_surface_two_band_texture";
inline constexpr const char* kWaterBodyTexture = "Water_body_texture";
inline constexpr const char* kWaterBodyTwoBandTexture = "Water_body_two_band_texture";
inline constexpr std::array<const char*, 3> kWaterOneBandTextures = {
    "Water_only_dark_texture", "Water_only_medium_texture", "Water_only_bright_texture"};

// Whether the water's flow regions are drawn (with toon shading, not as lines alone), and
// whether its flow lines are (with toon shading, not as regions alone).
bool draws_flow_regions(const SceneConfig& config);
bool draws_flow_lines(const SceneConfig& config);

// The limits of the water's toon classes on its coordinates, as scene.pov paints them: the
// bands' at water_thresholds, and the regions' where they are drawn.
ToonLimits water_toon_limits(const SceneLayout& layout);

// The light in POV-Ray's frame: the configured one, or a sun from above, left and front.
LightGeometry light_geometry(const LightConfig& light, Axis up);

// What the camera is known to be while a frame is written, for the render mesh's
// simplification (simplify.hpp): no point of the box [min, max] (POV-Ray frame) comes nearer to
// it than `nearest_distance`, for any sequence the box is part of.
struct CameraReach {
  double nearest_distance = 0;
  double angle_degrees = 0;   // horizontal field of view
  int width = 0, height = 0;  // image size
};
CameraReach camera_reach(const SceneLayout& layout, const Vec3& min, const Vec3& max);

std::string water_include_name(long frame);
std::string spray_include_name(long frame);
std::string foam_include_name(long frame);
std::string bubbles_include_name(long frame);
std::string object_include_name(const std::string& object_name, bool animated, long frame);
// PNG name POV-Ray gives a frame (padded to the digits of the last frame).
std::string frame_image_name(const SceneLayout& layout, long frame);

std::string scene_pov(const SceneLayout& layout);
std::string scene_ini(const SceneLayout& layout);
// The scene's toon.inc: the template's parts that scene.pov uses.
std::string scene_toon_inc(const SceneLayout& layout);

}  // namespace toonwater
