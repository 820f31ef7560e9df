// POV-Ray mesh2 text for a SceneMesh (POV-Ray 3.7 reference, "Mesh2"):
//
//   #declare Name = mesh2 {
//     vertex_vectors { N, <x,y,z>, ... }
//     normal_vectors { N, <x,y,z>, ... }    // indexed like the vertices; not in shells
//     uv_vectors     { N, <u,v>, ... }      // optional, indexed like the vertices
//     texture_list   { T, texture { Name }, ... }   // optional: one texture per face
//     face_indices   { F, <a,b,c>[, t], ... }   // no t: the object's texture
//     inside_vector  <x,y,z>                // closed meshes only
//   }
//
// Numbers are written with std::to_chars as fixed-point decimals into one buffer: positions
// with 7 significant digits relative to the mesh's largest coordinate (POV-Ray stores vertices
// in single precision), normals and texture coordinates with 6 decimals, trailing zeros
// dropped. NaN and Inf cannot occur (SceneMesh holds finite values) and are rejected if they do.
#pragma once

#include "scene/scene_mesh.hpp"

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace toonwater {

// The largest |coordinate| a scene's meshes may have: positions are written as fixed-point
// integers of up to 9e18 (with at least no decimal), and outline shells lie a little outside
// their meshes. A mesh beyond it is refused as bad input (check_scene_extent).
constexpr double largest_scene_coordinate = 1e18;

// Throws InputError naming `source` where `mesh` reaches beyond largest_scene_coordinate.
void check_scene_extent(const SceneMesh& mesh, const std::filesystem::path& source);

// Per-face textures: face f gets the declared texture `names[index[f]]`, or, with
// `object_texture`, none of its own: the texture the object is given (written without an
// index, which saves the scene the bytes on most faces).
struct FaceTextures {
  static constexpr std::uint8_t object_texture = 255;
  std::vector<std::string> names;
  std::vector<std::uint8_t> index;  // one per face of the mesh
};

// Appends `#declare identifier = mesh2 {...}` to `out`. `uv` is empty or one per vertex;
// `textures` null or one index per face.
void append_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                  std::span<const TextureCoordinate> uv, const FaceTextures* textures = nullptr);

// Per face: its normal (wound to agree with the vertex normals) points up,
// n·y > shell_min_up_component — the free surface of a closed liquid volume with the rounded
// edge round to its walls, as opposed to its walls and floor (free_surface.hpp says why not the
// free-surface selection).
std::vector<bool> upward_faces(const SceneMesh& mesh);

// Face t wound so that POV-Ray's face normal (a−b)×(c−b) agrees with its vertex normals: how
// the shell writes it.
Triangle shell_winding(const SceneMesh& mesh, const Triangle& t);

// Appends the outline shell of `mesh`: the same faces with vertex v moved by `offsets[v]` along
// its normal (Raskar and Cohen 1999), each face wound so that POV-Ray's face normal points
// outward, without normals or texture coordinates (the shell is drawn flat). With `keep`, only
// the faces it marks and the vertices they use (then the shell is open; an empty union when no
// face is marked), at the precision of the whole shell.
void append_shell_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                        std::span<const double> offsets, const std::vector<bool>* keep = nullptr);

}  // namespace toonwater
