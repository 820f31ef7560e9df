// Wavefront OBJ output of a triangle mesh: an optional `# comment` line, `v x y z` with each
// coordinate the shortest decimal that reads back as the same double (std::to_chars), so a mesh
// written and read again is the same to the bit, then `f i j k` (1-based). The one OBJ writer
// of the simulation, the report, the tests and the benchmarks.
#pragma once

#include "analyzer/mesh.hpp"

#include <filesystem>
#include <string>
#include <string_view>

namespace toonwater {

// The OBJ text of `mesh`, under `comment` when it is not empty. Throws std::invalid_argument on
// a NaN or infinite coordinate: such a mesh is never written.
std::string obj_text(const TriangleMesh& mesh, std::string_view comment = {});

// obj_text written atomically (common/atomic_file.hpp). Throws OutputError.
void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               std::string_view comment = {});

}  // namespace toonwater
