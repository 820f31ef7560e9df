// The OpenVDB module's entry (vdb_module.hpp) and what its parts share (vdb_parts.hpp).
#include "analyzer/readers/vdb/vdb_parts.hpp"

#include <openvdb/points/AttributeArray.h>

#include <mutex>

namespace toonwater {

void initialise_openvdb() {
  static std::once_flag initialised;
  std::call_once(initialised, [] {
    openvdb::initialize();
    // Mantaflow registers these before it reads its own files; a file that uses them cannot be
    // read without them ("unregistered type int32_trnc").
    using openvdb::points::TruncateCodec;
    using openvdb::points::TypedAttributeArray;
    if (!TypedAttributeArray<float, TruncateCodec>::isRegistered())
      TypedAttributeArray<float, TruncateCodec>::registerType();
    if (!TypedAttributeArray<int, TruncateCodec>::isRegistered())
      TypedAttributeArray<int, TruncateCodec>::registerType();
    if (!TypedAttributeArray<openvdb::Vec3f, TruncateCodec>::isRegistered())
      TypedAttributeArray<openvdb::Vec3f, TruncateCodec>::registerType();
  });
}

std::optional<openvdb::Vec3i> mantaflow_resolution(const openvdb::GridBase& grid) {
  const auto resolution = grid.getMetadata<openvdb::Vec3IMetadata>("file_base_resolution");
  if (!resolution) return std::nullopt;
  const openvdb::Vec3i res = resolution->value();
  if (res.x() <= 0 || res.y() <= 0 || res.z() <= 0) return std::nullopt;
  return res;
}

namespace {

const VdbModule module{vdb_module_interface_version, mesh_level_set, read_point_grid};

}  // namespace
}  // namespace toonwater

extern "C" __attribute__((visibility("default"))) const toonwater::VdbModule*
toonwater_vdb_module_entry() {
  return &toonwater::module;
}
