// The OpenVDB side of read_particles (vdb_module.hpp): a point grid's positions, kinds and
// velocities.
#include "analyzer/readers/vdb/vdb_parts.hpp"

#include <openvdb/points/PointCount.h>
#include <openvdb/points/PointDataGrid.h>

#include <algorithm>
#include <cmath>

namespace toonwater {
namespace {

// Mantaflow's particle flags (ParticleBase in Mantaflow's particle.h).
constexpr int mantaflow_spray = 2, mantaflow_bubble = 4, mantaflow_foam = 8;

ParticleKind kind_of_flags(int flags) {
  const int kind_bits = flags & (mantaflow_spray | mantaflow_bubble | mantaflow_foam);
  if (kind_bits == mantaflow_spray) return ParticleKind::spray;
  if (kind_bits == mantaflow_bubble) return ParticleKind::bubble;
  if (kind_bits == mantaflow_foam) return ParticleKind::foam;
  return ParticleKind::other;
}

// "particles_secondary", else the only point grid.
std::string choose_point_grid(const openvdb::GridPtrVec& grids) {
  std::string only, present;
  bool several = false;
  for (const auto& g : grids) {
    present += (present.empty() ? "'" : ", '") + g->getName() + "' (" + g->valueType() + ")";
    if (!g->isType<openvdb::points::PointDataGrid>()) continue;
    if (g->getName() == "particles_secondary") return g->getName();
    several = !only.empty();
    only = g->getName();
  }
  if (only.empty())
    throw std::runtime_error("no point grid; its grids: " + (present.empty() ? "none" : present));
  if (several)
    throw std::runtime_error(
        "more than one point grid and none named 'particles_secondary'; "
        "its grids: " +
        present);
  return only;
}

Vec3 to_vec3(const openvdb::Vec3d& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

ParticleSet read_point_grid(const std::string& path) {
  initialise_openvdb();
  openvdb::points::PointDataGrid::Ptr grid;
  std::string name;
  read_vdb_file([&] {
    openvdb::io::File file(path);
    file.open(false);
    name = choose_point_grid(*file.readAllGridMetadata());
    grid = openvdb::gridPtrCast<openvdb::points::PointDataGrid>(file.readGrid(name));
    file.close();
  });
  if (!grid) throw std::runtime_error("grid '" + name + "' is not a point grid");
  const std::optional<openvdb::Vec3i> mantaflow = mantaflow_resolution(*grid);
  const double longest =
      mantaflow ? std::max({mantaflow->x(), mantaflow->y(), mantaflow->z()}) : 1.0;
  const openvdb::Vec3d half_resolution =
      mantaflow ? openvdb::Vec3d(*mantaflow) * 0.5 : openvdb::Vec3d(0.0);

  ParticleSet out;
  const auto leaf = grid->tree().cbeginLeaf();
  if (!leaf) return out;
  const openvdb::points::AttributeSet::Descriptor& descriptor = leaf->attributeSet().descriptor();
  const std::size_t position_index = descriptor.find("P");
  if (position_index == openvdb::points::AttributeSet::INVALID_POS)
    throw std::runtime_error("point grid '" + name + "' has no positions (attribute 'P')");
  const std::size_t flags_index = descriptor.find("U");
  std::size_t velocity_index = descriptor.find("particles_velocity_secondary");
  if (velocity_index == openvdb::points::AttributeSet::INVALID_POS)
    velocity_index = descriptor.find("particles_velocity");
  const bool has_flags = flags_index != openvdb::points::AttributeSet::INVALID_POS;
  const bool has_velocity = velocity_index != openvdb::points::AttributeSet::INVALID_POS;

  const openvdb::Index64 count = openvdb::points::pointCount(grid->tree());
  out.positions.reserve(count);
  out.kinds.reserve(count);
  if (has_velocity) out.velocities.reserve(count);
  const openvdb::math::Transform& transform = grid->transform();
  for (auto l = grid->tree().cbeginLeaf(); l; ++l) {
    const openvdb::points::AttributeHandle<openvdb::Vec3f> position(
        l->constAttributeArray(position_index));
    std::unique_ptr<openvdb::points::AttributeHandle<int>> flags;
    if (has_flags)
      flags = std::make_unique<openvdb::points::AttributeHandle<int>>(
          l->constAttributeArray(flags_index));
    std::unique_ptr<openvdb::points::AttributeHandle<openvdb::Vec3f>> velocity;
    if (has_velocity)
      velocity = std::make_unique<openvdb::points::AttributeHandle<openvdb::Vec3f>>(
          l->constAttributeArray(velocity_index));
    for (auto index = l->beginIndexOn(); index; ++index) {
      // OpenVDB's convention: P is the offset from its voxel's centre, in index units.
      const openvdb::Vec3d in_index = index.getCoord().asVec3d() + position.get(*index);
      const Vec3 p = mantaflow ? to_vec3((in_index - half_resolution) / longest)
                               : to_vec3(transform.indexToWorld(in_index));
      if (!p.allFinite())
        throw std::runtime_error("point " + std::to_string(out.positions.size()) +
                                 " has a NaN or infinite position");
      out.positions.push_back(p);
      out.kinds.push_back(flags ? kind_of_flags(flags->get(*index)) : ParticleKind::other);
      if (velocity) {
        const Vec3 v = to_vec3(velocity->get(*index));
        if (!v.allFinite())
          throw std::runtime_error("point " + std::to_string(out.positions.size() - 1) +
                                   " has a NaN or infinite velocity");
        out.velocities.push_back(v);
      }
    }
  }
  return out;
}

}  // namespace toonwater
