// Internal to the OpenVDB module (vdb_module.hpp): its parts, one file each, and what they share.
// Every function throws std::runtime_error (or an openvdb::Exception) with the reason, not
// naming the file.
#pragma once

#include "analyzer/readers/vdb/vdb_module.hpp"

#include <openvdb/openvdb.h>

#include <functional>
#include <optional>
#include <stdexcept>
#include <string>

namespace toonwater {

// openvdb::initialize() and the attribute types Mantaflow writes (TruncateCodec), once.
void initialise_openvdb();

// Mantaflow's base resolution when the grid is Mantaflow's (the `file_base_resolution`
// metadata Mantaflow writes on every grid it saves), else nothing.
std::optional<openvdb::Vec3i> mantaflow_resolution(const openvdb::GridBase& grid);

// Runs `read`, OpenVDB reading a file, and turns what a truncated or damaged file makes it
// throw into one short std::runtime_error line: OpenVDB's reason, which can hold kilobytes of
// the file where a grid's type name belongs, cut short; std::bad_alloc or std::length_error
// from a length the file's bytes state. Only the reading: a failure after it is not the file's.
void read_vdb_file(const std::function<void()>& read);

MeshedLevelSet mesh_level_set(const std::string& path, const std::string& grid, double adaptivity);
ParticleSet read_point_grid(const std::string& path);

}  // namespace toonwater
