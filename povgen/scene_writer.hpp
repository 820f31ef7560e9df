// scene.pov and scene.ini: the parts of a toonwater scene that are the same for every frame.
// scene.pov includes templates/toon.inc and, per frame, the mesh2 includes the frame writer
// produced (water_NNNN.inc, obj_NAME.inc or obj_NAME_NNNN.inc). It contains only what the
// configuration needs: no light without highlights, no reflection finish or reflection targets
// when the water does not reflect, no interior when nothing refracts, no shells without
// outlines, no flow pigment without flow regions, no object code without objects.
//
// Everything written comes from validated values: finite numbers, known keywords and
// identifiers the configuration sanitised.
#pragma once

#include "povgen/config.hpp"
#include "povgen/scene_mesh.hpp"

#include <string>
#include <vector>

namespace toonwater::povgen {

struct ObjectPlacement {
  const ObjectConfig* config = nullptr;
  bool animated = false;   // one mesh per frame
  bool submerged = false;  // below the water's top in some frame: its shell takes the water's ior
};

struct SceneLayout {
  const SceneConfig* config = nullptr;
  Axis up = Axis::y;
  Vec3 water_min = Vec3::Zero(), water_max = Vec3::Zero();  // POV-Ray frame, all frames
  std::vector<ObjectPlacement> objects;
  bool animation = false;  // false: one frame, written as frame 0
  long first_frame = 0, last_frame = 0;
};

// The light in POV-Ray's frame: the configured one, or a sun from above, left and front.
LightGeometry light_geometry(const LightConfig& light, Axis up);

// What the camera is known to be while a frame is written, for the render mesh's
// simplification (simplify.hpp): no point of the box [min, max] (POV-Ray frame) comes nearer to
// it than `nearest_distance`, for any sequence the box is part of.
struct CameraReach {
  double nearest_distance = 0;
  double angle_degrees = 0;  // horizontal field of view
  int width = 0, height = 0;  // image size
};
CameraReach camera_reach(const SceneLayout& layout, const Vec3& min, const Vec3& max);

std::string water_include_name(long frame);
std::string object_include_name(const std::string& object_name, bool animated, long frame);
// PNG name POV-Ray gives a frame (padded to the digits of the last frame).
std::string frame_image_name(const SceneLayout& layout, long frame);

std::string scene_pov(const SceneLayout& layout);
std::string scene_ini(const SceneLayout& layout);

}  // namespace toonwater::povgen
