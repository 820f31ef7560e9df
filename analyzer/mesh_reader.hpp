// Strict readers for OBJ, OFF, PLY (ASCII and binary) and STL (ASCII and binary).
//
// Why not OpenMesh's readers: they parse OBJ and OFF coordinates in single precision, skip
// malformed lines silently (which shifts every later vertex index), drop repeated face corners
// and report no line numbers. The analyzer needs double precision and a clear error naming the
// file and line, so the readers here are our own; they fill flat arrays directly.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string>

namespace toonwater {

// A problem with an input file. what() is one line: "FILE:LINE: message" (or "FILE: message").
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A well-formed file that holds no face (a simulation frame with no liquid, say). Sequence
// tools catch it to skip the frame; everywhere else it is an InputError like any other.
class EmptyMeshError : public InputError {
 public:
  using InputError::InputError;
};

struct InputMesh {
  // Vertices in file order (STL: one per facet corner, in file order), polygons triangulated as
  // fans in file order.
  TriangleMesh mesh;
  std::size_t polygon_count = 0;  // faces as the file lists them, before triangulation
};

// How an OpenVDB level set is meshed (readers/vdb/vdb_module.hpp).
struct LevelSetOptions {
  std::string grid;         // empty: surface, then phi, then the only level-set grid
  double adaptivity = 0.0;  // OpenVDB's volumeToMesh, in [0, 1]
};

// Reads OBJ/OFF/PLY/STL, legacy VTK, Mantaflow's .bobj.gz, FLIP Fluids' .bobj or an OpenVDB level
// set (.vdb, meshed as `level_set` says), chosen by the file's extension (case-insensitive). Throws
// InputError for a missing, unreadable, malformed or truncated file, an index out of range, a face
// with fewer than three corners, or a coordinate that is NaN or infinite.
InputMesh read_mesh(const std::filesystem::path& path, const LevelSetOptions& level_set = {});

}  // namespace toonwater
