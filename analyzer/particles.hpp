// Secondary particles of one simulation frame — spray, foam and bubbles (and FLIP Fluids' dust)
// — as the fluid tools bake them beside the surface, read into one set with kinds, positions and,
// where the file carries them, velocities.
//
// Formats (docs/inputs.md):
// - a Mantaflow particle cache, `cache_fluid/particles/fluid_particles_NNNN.vdb`: the OpenVDB
//   point grid `particles_secondary`, its kind from the flag bits of attribute `U` (2 spray,
//   4 bubble, 8 foam), velocity `particles_velocity_secondary`; positions in the normalised
//   domain coordinates of Mantaflow's mesh cache, so that the bake's --scale/--translate place
//   them (readers/vdb/vdb_module.hpp);
// - a FLIP Fluids whitewater file, `bakefiles/{foam,bubble,spray,dust}NNNNNN.wwp`: one kind per
//   file, named by its prefix; positions in world units, no velocities.
#pragma once

#include "analyzer/mesh.hpp"

#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

namespace toonwater {

enum class ParticleKind : std::uint8_t { spray, foam, bubble, dust, other };

struct ParticleSet {
  std::vector<Vec3> positions;
  std::vector<ParticleKind> kinds;  // one per particle
  std::vector<Vec3> velocities;     // one per particle, or none when the file has none
};

// "spray", "foam", "bubble", "dust", "other".
std::string_view kind_name(ParticleKind kind);

std::size_t count_of(const ParticleSet& particles, ParticleKind kind);

// Reads the particles of one file, chosen by its extension (.vdb, .wwp). Throws InputError for a
// missing, malformed or truncated file, a file with no particle grid, or a NaN or infinite value;
// VdbModuleError when a .vdb needs the OpenVDB module and it cannot be loaded.
ParticleSet read_particles(const std::filesystem::path& path);

}  // namespace toonwater
