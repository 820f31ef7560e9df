// From the input's axes to POV-Ray's: y up, left-handed, without mirroring the picture.
//
// Simulation output (Blender, Mantaflow, OBJ in general) is right-handed. POV-Ray's frame is
// left-handed, so the coordinate map must have determinant −1: as a map between the two physical
// spaces it is then a rotation, and a camera placed with the same coordinates sees the same,
// un-mirrored picture. The up axis goes to y; the other two follow so that a viewer looking
// along the input's "forward" axis keeps +x (or the next axis) on the right:
//
//   --up y:  (x, y, z) -> (x, y, −z)   camera on +z looking at −z  -> camera on −z looking at +z
//   --up z:  (x, y, z) -> (x, z,  y)   Blender's front view (from −y) -> POV-Ray's default view
//   --up x:  (x, y, z) -> (y, x,  z)   the cyclic relabelling (y, z, x) of the z-up case
//
// The map is orthogonal, so it carries normals, directions and lengths unchanged.
#pragma once

#include "analyzer/mesh.hpp"

namespace toonwater {

inline Vec3 to_povray(const Vec3& p, Axis up) {
  switch (up) {
    case Axis::x:
      return {p.y(), p.x(), p.z()};
    case Axis::z:
      return {p.x(), p.z(), p.y()};
    case Axis::y:
      break;
  }
  return {p.x(), p.y(), -p.z()};
}

}  // namespace toonwater
