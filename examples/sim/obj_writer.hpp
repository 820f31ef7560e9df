// Wavefront OBJ output for the simulation's frames: `v x y z` with 9 significant digits (more
// than POV-Ray's single precision keeps; ripple curvature is unaffected), then `f i j k`
// (1-based). Written atomically (analyzer/atomic_file.hpp).
#pragma once

#include "analyzer/mesh.hpp"

#include <filesystem>
#include <string>
#include <string_view>

namespace toonwater::sim {

// The OBJ text of `mesh` under a one-line comment. Throws std::invalid_argument on a NaN or
// infinite coordinate: such a frame is never written.
std::string obj_text(const TriangleMesh& mesh, std::string_view comment);

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               std::string_view comment);

}  // namespace toonwater::sim
