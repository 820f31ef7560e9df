// The OpenVDB module's entry (vdb_module.hpp) and what its parts share (vdb_parts.hpp).
#include "analyzer/readers/vdb/vdb_parts.hpp"
#include "common/printable_text.hpp"

#include <openvdb/points/AttributeArray.h>

#include <mutex>
#include <new>
#include <stdexcept>
#include <string_view>

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

const std::string unreadable_prefix = "OpenVDB cannot read it (a truncated or damaged file?): ";

std::runtime_error unreadable(const openvdb::Exception& e) {
  // OpenVDB's messages can span lines: each run of white space becomes one space.
  std::string reason;
  for (const char c : std::string_view(e.what())) {
    const bool white = c == ' ' || c == '\n' || c == '\t' || c == '\r';
    if (!white)
      reason += c;
    else if (!reason.empty() && reason.back() != ' ')
      reason += ' ';
  }
  constexpr std::size_t longest_reason = 160;
  return std::runtime_error(unreadable_prefix + printable_text(reason, longest_reason));
}

std::runtime_error unreadable_size() {
  return std::runtime_error(unreadable_prefix + "it states a size larger than memory");
}

}  // namespace

void read_vdb_file(const std::function<void()>& read) {
  try {
    read();
  } catch (const openvdb::Exception& e) {
    throw unreadable(e);
  } catch (const std::bad_alloc&) {
    throw unreadable_size();
  } catch (const std::length_error&) {
    throw unreadable_size();
  }
}

namespace {

const VdbModule module{vdb_module_interface_version, mesh_level_set, read_point_grid};

}  // namespace
}  // namespace toonwater

extern "C" __attribute__((visibility("default"))) const toonwater::VdbModule*
toonwater_vdb_module_entry() {
  return &toonwater::module;
}
