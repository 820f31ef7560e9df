// Outline shell faces no ray of the scene can see: dropped before they are written, as they
// are pure parse cost (a shell is an offset copy of the whole mesh, about half of a frame's
// parse time).
//
// How a shell draws (templates/toon.inc, Toon_outline_shell; Raskar and Cohen 1999): its front
// is `pigment { rgbt 1 }`, its back (interior_texture) the flat line colour. POV-Ray takes the
// interior texture where a ray meets a face from the side its normal points away from, and a
// shell mesh2 has no normal_vectors, so that normal is the face's own, (a−b)×(c−b) for
// <a,b,c>. A ray meeting a face from the front goes through unchanged: transmit 1 and filter 0
// let all of it pass, the finish adds nothing (no reflection, no highlight, diffuse and ambient
// 0), and the shell's interior has the default ior 1, the air's, so the ray does not bend. A face
// matters only to rays that meet it from behind.
//
// Camera rays all start at the camera's location E (a perspective camera). For a flat
// triangle with normal N through its vertex a, every point p of its plane has
// (p − E)·N = (a − E)·N: every camera ray meets the triangle from the same side, from the front
// exactly when (E − a)·N > 0. Passing through other shell fronts does not bend a camera ray.
//
// Rays change direction only at surfaces that reflect or refract. In a toonwater scene only
// the water does (water.reflection, water.transmit with its ior); objects have flat bands and
// no reflection, flow lines are opaque, the sky is seen in reflections only. So when
//   - the water does not refract (no refracted ray anywhere in the scene), and
//   - the water does not reflect, or the shell is no_reflection (scene_writer.cpp: the water's
//     shell whenever the water reflects, an object's when its reflection target is none),
// every ray that meets the shell is a camera ray, and the faces that face the camera can be
// dropped without changing a pixel.
//
// With refraction nothing is dropped, and no rule from the camera alone can drop anything:
//   - A ray refracted into the water that meets the surface again from inside, at a face with
//     normal N, leaves it (or, past the critical angle, is reflected inside, and can meet
//     another face) going outward, d·N > 0. The face's shell lies its offset outside that face,
//     with the same outward normal, so the leaving ray meets the shell from behind: a line
//     pixel, seen through the water. Which faces such rays reach depends on the whole path
//     through the water (entry face, ior, internal reflections), not on where the camera is: a
//     face that faces the camera can be one of them (a ray entering one side of a crest and
//     leaving through its top), so camera culling could drop a face a ray meets.
//   - POV-Ray 3.7 cannot keep refracted rays off an object: its ray-type modifiers are
//     no_image, no_reflection, no_shadow and no_radiosity. no_image hides an object from camera
//     rays and from their refracted continuations alike (both are the same ray once it has
//     passed through a transparent surface), so it would hide the camera's outlines too; no
//     other construct (clipped_by, a bounding object, an interior) distinguishes the two rays.
// Keeping only the faces such rays can reach would take tracing the refracted rays of every
// pixel with POV-Ray's own arithmetic before writing the scene; that is not done.
//
// Two more differences between passing a front face and not meeting it at all:
//   - One trace level less per dropped face: this changes a pixel only where a ray ran out of
//     max_trace_level (the tests check that none did).
//   - POV-Ray continues a ray that went through a surface from the hit point and ignores hits
//     closer than kPovrayMinimumDepth (1e-4 scene units, MIN_ISECT_DEPTH in POV-Ray's source).
//     So the ray that passed a front face at p does not see a surface within that distance of p,
//     and the same ray in the culled scene does: dropping the face shows it. Measured: single
//     antialiasing samples changed beside the kept faces and where an object's shell meets the
//     water's. So a face is dropped only when nothing but dropped faces can lie that near it:
//     not beside a kept face (the faces sharing a vertex with one stay), not near an object or
//     its shell (faces whose box comes within the object's box grown by its shell offset stay),
//     not closer to the water than kMinimumOffset (ten times POV-Ray's minimum depth; the
//     shell lies its offset above the water), and not when flow lines (strokes on the water)
//     are drawn. The pixel tests on every example check the whole rule.
//
// POV-Ray reads the written positions, rounded to 7 significant digits of the largest
// coordinate (mesh2_writer.hpp) and stored in single precision; a face is dropped only when
// (E − a)·N stays positive for every vertex moved by that rounding (kPositionError).
#pragma once

#include "scene/config.hpp"
#include "scene/scene_mesh.hpp"

#include <span>
#include <vector>

namespace toonwater {

// Whether every ray that can meet a shell is a camera ray, as above: the water does not
// refract, and it does not reflect or the shell is no_reflection.
bool shell_met_by_camera_rays_only(const SceneConfig& config, bool shell_no_reflection);

// A box that shell faces must keep away from to be dropped: an object (and its shell).
struct KeepOutBox {
  Vec3 min = Vec3::Zero(), max = Vec3::Zero();
};

// Per face of `mesh`'s shell (vertex v moved by offsets[v] along its normal, faces wound as
// append_shell_mesh2 writes them): whether it is kept, by the rule above for a camera at `eye`:
// a camera ray can meet it from behind, or it is beside such a face, near one of `keep_out`, or
// has a vertex offset below kMinimumOffset. With `keep`, faces it does not mark are not kept.
std::vector<bool> shell_faces_seen_from_behind(const SceneMesh& mesh,
                                               std::span<const double> offsets, const Vec3& eye,
                                               std::span<const KeepOutBox> keep_out = {},
                                               const std::vector<bool>* keep = nullptr);

}  // namespace toonwater
