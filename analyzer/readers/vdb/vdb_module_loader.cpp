// vdb_module() for the toonwater program: loads toonwater-vdb.so from beside the program
// (common/module_loader.hpp) when it first reads a .vdb file, and keeps it loaded. See
// vdb_module.hpp.
#include "analyzer/readers/vdb/vdb_module.hpp"

#include "common/module_loader.hpp"

namespace toonwater {
namespace {

const VdbModule* load_vdb_module() {
  const LoadedModule module =
      load_module_beside_program("toonwater-vdb.so", "toonwater_vdb_module_entry");
  if (!module.entry)
    throw VdbModuleError(module.path.string() + ": cannot load the OpenVDB module (" +
                         module.error +
                         "); it must lie beside the toonwater program for .vdb files to be read");
  using Entry = const VdbModule* (*)();
  const VdbModule* loaded = reinterpret_cast<Entry>(module.entry)();
  if (!loaded || loaded->interface_version != vdb_module_interface_version)
    throw VdbModuleError(module.path.string() +
                         ": the OpenVDB module belongs to another build of toonwater");
  return loaded;
}

}  // namespace

const VdbModule& vdb_module() {
  static const VdbModule* module = load_vdb_module();  // thread-safe; retried after a failure
  return *module;
}

}  // namespace toonwater
