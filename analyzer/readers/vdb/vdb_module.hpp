// What toonwater reads through OpenVDB: level sets as meshes, and Mantaflow's particle caches.
//
// Level sets: the surface of a Houdini FLIP `surface` grid, Mantaflow's
// liquid level set `phi`, or any signed-distance grid, meshed at its zero level with OpenVDB's
// own mesher, tools::volumeToMesh (dual contouring on the grid's active voxels; `adaptivity` in
// [0, 1] merges coplanar cells, 0 keeps every cell), its quads split into triangles and every
// face oriented so that its normal points out of the liquid (towards positive distance).
//
// Coordinates: a Mantaflow grid (recognised by the `file_base_resolution` metadata Mantaflow
// writes on every grid) is read in the normalised domain coordinates of Mantaflow's mesh cache,
// cell centres (i + ½) with the domain's centre at 0 and its longest side 1, so that the same
// --scale (the longest side) and --translate (the centre) put the mesh cache and the level set
// of one bake in one place (../shared/data/mantaflow-dambreak/README.md). Any other grid keeps
// its own transform as world coordinates.
//
// The grid: the one named (a float or double grid that is not a fog volume: a signed distance
// field may carry no class), else "surface", else "phi", else the only float or double grid
// whose class is level set; otherwise an error that lists the grids the file holds.
//
// Particles: the point grid `particles_secondary` (Mantaflow's secondary particles), else the
// only point grid; positions from OpenVDB's convention, index-space voxel + P, and, for a
// Mantaflow grid, in its mesh cache's normalised coordinates without the half cell (points are
// not cell centres): v = (voxel + P − res/2) / max(res). Mantaflow stores its point attributes
// with OpenVDB's TruncateCodec (half floats, int16), whose types it registers before it reads;
// so does this module. Kinds from the bits of `U`: 2 spray, 4 bubble, 8 foam (Mantaflow's
// ParticleBase::PSPRAY, PBUBBLE, PFOAM); velocities from `particles_velocity_secondary` (or
// `particles_velocity`) as stored, in Mantaflow's grid units.
//
// Why a module: OpenVDB pulls in Boost, Blosc and more, which every run of the toonwater
// program would otherwise load. Its implementation (level_set_mesher.cpp) is built into
// toonwater-vdb.so, which the program loads from beside its executable when it first reads a
// .vdb file (vdb_module_loader.cpp); tests link the same implementation statically
// (vdb_module_linked.cpp). A program links exactly one of the two.
#pragma once

#include "analyzer/mesh.hpp"
#include "analyzer/particles.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {

struct MeshedLevelSet {
  TriangleMesh mesh;      // world coordinates, or Mantaflow's normalised ones (above)
  std::string grid;       // the grid meshed
  double voxel_size = 0;  // its voxel size along x
};

// Every function throws std::runtime_error with the reason (not naming the file) on failure.
struct VdbModule {
  int interface_version = 0;  // vdb_module_interface_version of the code that built it
  MeshedLevelSet (*mesh_level_set)(const std::string& path, const std::string& grid,
                                   double adaptivity) = nullptr;
  ParticleSet (*read_point_grid)(const std::string& path) = nullptr;
};

inline constexpr int vdb_module_interface_version = 2;

// The module is missing or unusable: the installation is incomplete.
class VdbModuleError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The module, loaded on first use. Throws VdbModuleError when it cannot be loaded.
const VdbModule& vdb_module();

}  // namespace toonwater

extern "C" const toonwater::VdbModule* toonwater_vdb_module_entry();
