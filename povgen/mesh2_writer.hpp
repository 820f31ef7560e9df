// POV-Ray mesh2 text for a SceneMesh (POV-Ray 3.7 reference, "Mesh2"):
//
//   #declare Name = mesh2 {
//     vertex_vectors { N, <x,y,z>, ... }
//     normal_vectors { N, <x,y,z>, ... }    // indexed like the vertices; not in shells
//     uv_vectors     { N, <u,v>, ... }      // optional, indexed like the vertices
//     face_indices   { F, <a,b,c>, ... }
//     inside_vector  <x,y,z>                // closed meshes only
//   }
//
// Numbers are written with std::to_chars as fixed-point decimals into one buffer: positions
// with 7 significant digits relative to the mesh's largest coordinate (POV-Ray stores vertices
// in single precision), normals and texture coordinates with 6 decimals, trailing zeros
// dropped. NaN and Inf cannot occur (SceneMesh holds finite values) and are rejected if they do.
#pragma once

#include "povgen/scene_mesh.hpp"

#include <span>
#include <string>
#include <string_view>

namespace toonwater::povgen {

// Appends `#declare identifier = mesh2 {...}` to `out`. `uv` is empty or one per vertex.
void append_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                  std::span<const TextureCoordinate> uv);

// Which faces an outline shell keeps.
enum class ShellFaces {
  all,
  // Faces whose normal points up (n·y > 0.1): the free surface of a closed liquid volume. Rays
  // refracted through a transparent closed volume leave it through its floor and walls and would
  // meet the inside of a closed shell there, painting the water in the line colour.
  upward,
};

// Appends the outline shell of `mesh`: the same faces with every vertex moved by `offset` along
// its normal (Raskar and Cohen 1999), each face wound so that POV-Ray's face normal points
// outward, without normals or texture coordinates (the shell is drawn flat).
void append_shell_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                        double offset, ShellFaces faces = ShellFaces::all);

}  // namespace toonwater::povgen
