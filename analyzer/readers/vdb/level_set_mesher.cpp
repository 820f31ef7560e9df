// The OpenVDB side of vdb_module.hpp: choose a grid, mesh its zero level, orient it.
#include "analyzer/readers/vdb/vdb_parts.hpp"

#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <optional>

namespace toonwater {
namespace {

bool is_scalar(const openvdb::GridBase& grid) {
  return grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::DoubleGrid>();
}

std::string describe(const openvdb::GridBase& grid) {
  return "'" + grid.getName() + "' (" + grid.valueType() + ", " +
         openvdb::GridBase::gridClassToString(grid.getGridClass()) + ")";
}

// The grid to mesh among the file's (metadata only), by the rule of vdb_module.hpp.
std::string choose_grid(const openvdb::GridPtrVec& grids, const std::string& wanted) {
  auto find = [&](const std::string& name) -> const openvdb::GridBase* {
    for (const auto& g : grids)
      if (g && g->getName() == name) return g.get();
    return nullptr;
  };
  std::string present;
  for (const auto& g : grids) present += (present.empty() ? "" : ", ") + describe(*g);
  if (present.empty()) present = "none";
  if (!wanted.empty()) {
    const openvdb::GridBase* g = find(wanted);
    if (!g) throw std::runtime_error("no grid named '" + wanted + "'; its grids: " + present);
    if (!is_scalar(*g))
      throw std::runtime_error("grid " + describe(*g) + " is not a float or double grid");
    // A signed distance field may carry no class ("unknown"); a fog volume is a density.
    if (g->getGridClass() == openvdb::GRID_FOG_VOLUME ||
        g->getGridClass() == openvdb::GRID_STAGGERED)
      throw std::runtime_error("grid " + describe(*g) + " is not a level set or a signed distance");
    return wanted;
  }
  for (const char* name : {"surface", "phi"})
    if (const openvdb::GridBase* g = find(name); g && is_scalar(*g)) return name;
  const openvdb::GridBase* only = nullptr;
  for (const auto& g : grids) {
    if (!is_scalar(*g) || g->getGridClass() != openvdb::GRID_LEVEL_SET) continue;
    if (only)
      throw std::runtime_error("more than one level-set grid; choose one with --grid; its grids: " +
                               present);
    only = g.get();
  }
  if (!only)
    throw std::runtime_error(
        "no level-set grid ('surface', 'phi' or one of class level set); "
        "its grids: " +
        present);
  return only->getName();
}

// A grid larger in memory than the machine is refused before it is read: OpenVDB writes the
// size of each grid's tree with it (`file_mem_bytes`), and a dense grid of zeros, small on disk,
// can take more memory than there is.
void check_fits_in_memory(const openvdb::GridBase& grid) {
  const auto bytes =
      grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_MEM_BYTES);
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (!bytes || bytes->value() <= 0 || pages <= 0 || page <= 0) return;
  const auto memory = static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page);
  if (static_cast<std::uint64_t>(bytes->value()) > memory)
    throw std::runtime_error("grid '" + grid.getName() + "' takes " +
                             std::to_string(static_cast<std::uint64_t>(bytes->value()) >> 30) +
                             " GiB in memory, more than this machine's " +
                             std::to_string(memory >> 30) + " GiB");
}

// A point of the grid's world in Mantaflow's normalised domain coordinates, those of its mesh
// cache (.bobj.gz): its cell centres (i + ½) with the domain's centre at 0 and its longest side
// 1, v = (i + ½ − res/2) / max(res).
Vec3 normalised(const openvdb::GridBase& grid, const openvdb::Vec3s& p, const openvdb::Vec3i& res) {
  const openvdb::Vec3d index = grid.transform().worldToIndex(openvdb::Vec3d(p));
  const double longest = std::max({res.x(), res.y(), res.z()});
  return {(index.x() + 0.5 - 0.5 * res.x()) / longest, (index.y() + 0.5 - 0.5 * res.y()) / longest,
          (index.z() + 0.5 - 0.5 * res.z()) / longest};
}

// Mantaflow's domain is walled by its outermost layer of cells, where phi is extrapolated from the
// liquid beside them; Mantaflow closes its own mesh there by raising that layer to half a cell
// outside (its save_mesh: `setBound(0.5, 0)` on a copy of phi). The same here, so that the
// level set's mesh meets the walls where the mesh cache does, not half a cell beyond the domain.
template <class Grid>
void close_at_domain_walls(Grid& grid, const openvdb::Vec3i& resolution) {
  using Value = typename Grid::ValueType;
  constexpr Value outside = Value(0.5);  // phi is in cells
  auto accessor = grid.getAccessor();
  for (int axis = 0; axis < 3; ++axis) {
    const int u_axis = (axis + 1) % 3, v_axis = (axis + 2) % 3;
    for (const int layer : {0, resolution[axis] - 1})
      for (int u = 0; u < resolution[u_axis]; ++u)
        for (int v = 0; v < resolution[v_axis]; ++v) {
          openvdb::Coord ijk;
          ijk[axis] = layer;
          ijk[u_axis] = u;
          ijk[v_axis] = v;
          if (accessor.getValue(ijk) < outside) accessor.setValue(ijk, outside);
        }
  }
}

// A level set holds distances: a NaN one (a damaged file, a solver that blew up) has no zero
// crossing to mesh, and OpenVDB's mesher refuses NaN and -inf but meshes +inf. Every value,
// the background and inactive ones included (the mesher reads neighbours), must be finite.
template <class Grid>
void check_finite(const Grid& grid) {
  if (!std::isfinite(grid.background()))
    throw std::runtime_error("grid '" + grid.getName() + "' has a non-finite background distance");
  for (auto value = grid.cbeginValueAll(); value; ++value)
    if (!std::isfinite(*value)) {
      const openvdb::Coord ijk = value.getCoord();
      throw std::runtime_error(
          "grid '" + grid.getName() + "' holds a NaN or infinite distance at " +
          (value.isVoxelValue() ? "voxel (" : "the tile at (") + std::to_string(ijk.x()) + ", " +
          std::to_string(ijk.y()) + ", " + std::to_string(ijk.z()) + ")");
    }
}

template <class Grid>
TriangleMesh mesh_zero_level(Grid& grid, double adaptivity) {
  check_finite(grid);
  const std::optional<openvdb::Vec3i> mantaflow = mantaflow_resolution(grid);
  if (mantaflow) close_at_domain_walls(grid, *mantaflow);
  std::vector<openvdb::Vec3s> points;
  std::vector<openvdb::Vec3I> triangles;
  std::vector<openvdb::Vec4I> quads;
  openvdb::tools::volumeToMesh(grid, points, triangles, quads, 0.0, adaptivity);
  TriangleMesh mesh;
  mesh.positions.reserve(points.size());
  for (const auto& p : points)
    mesh.positions.push_back(mantaflow ? normalised(grid, p, *mantaflow)
                                       : Vec3(p.x(), p.y(), p.z()));
  mesh.triangles.reserve(triangles.size() + 2 * quads.size());
  // volumeToMesh winds its polygons clockwise seen from outside (towards positive distance):
  // reversed here, so that normals point out of the liquid.
  auto add = [&](unsigned a, unsigned b, unsigned c) {
    mesh.triangles.push_back(
        {static_cast<std::int32_t>(a), static_cast<std::int32_t>(c), static_cast<std::int32_t>(b)});
  };
  for (const auto& t : triangles) add(t[0], t[1], t[2]);
  for (const auto& q : quads) {
    add(q[0], q[1], q[2]);
    add(q[0], q[2], q[3]);
  }
  return mesh;
}

}  // namespace

MeshedLevelSet mesh_level_set(const std::string& path, const std::string& wanted,
                              double adaptivity) {
  initialise_openvdb();
  MeshedLevelSet out;
  openvdb::GridBase::Ptr grid;
  read_vdb_file([&] {
    openvdb::io::File file(path);
    file.open(false);
    const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
    out.grid = choose_grid(*grids, wanted);
    for (const auto& g : *grids)
      if (g && g->getName() == out.grid) check_fits_in_memory(*g);
    grid = file.readGrid(out.grid);
    file.close();
  });
  out.voxel_size = grid->voxelSize()[0];
  try {
    if (const auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(grid))
      out.mesh = mesh_zero_level(*f, adaptivity);
    else if (const auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(grid))
      out.mesh = mesh_zero_level(*d, adaptivity);
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(std::string("OpenVDB cannot mesh it: ") + e.what());
  }
  return out;
}

}  // namespace toonwater
