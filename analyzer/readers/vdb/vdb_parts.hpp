// Internal to the OpenVDB module (vdb_module.hpp): its parts, one file each, and what they share.
// Every function throws std::runtime_error (or an openvdb::Exception) with the reason, not
// naming the file.
#pragma once

#include "analyzer/readers/vdb/vdb_module.hpp"

#include <openvdb/openvdb.h>

#include <optional>
#include <stdexcept>
#include <string>

namespace toonwater {

// openvdb::initialize() and the attribute types Mantaflow writes (TruncateCodec), once.
void initialise_openvdb();

// Mantaflow's base resolution when the grid is Mantaflow's (the `file_base_resolution`
// metadata Mantaflow writes on every grid it saves), else nothing.
std::optional<openvdb::Vec3i> mantaflow_resolution(const openvdb::GridBase& grid);

// OpenVDB's reason for a file it cannot read, as one short line: a truncated or damaged file
// puts what it held where a grid's type name belongs, kilobytes of it, into the message.
std::runtime_error unreadable(const openvdb::Exception& e);

// A damaged file whose bytes, read as a length, ask for more memory than any machine has
// (std::bad_alloc or std::length_error from OpenVDB's reading), as one line.
std::runtime_error unreadable_size();

MeshedLevelSet mesh_level_set(const std::string& path, const std::string& grid, double adaptivity);
ParticleSet read_point_grid(const std::string& path);

}  // namespace toonwater
