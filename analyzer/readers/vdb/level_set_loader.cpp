// level_set_module() for the toonwater program: loads toonwater-vdb.so from beside the program
// (common/module_loader.hpp) when it first reads a .vdb file, and keeps it loaded. See
// level_set_module.hpp.
#include "analyzer/readers/vdb/level_set_module.hpp"

#include "common/module_loader.hpp"

namespace toonwater {
namespace {

const LevelSetModule* load_level_set_module() {
  const LoadedModule module =
      load_module_beside_program("toonwater-vdb.so", "toonwater_level_set_module_entry");
  if (!module.entry)
    throw LevelSetModuleError(
        module.path.string() + ": cannot load the OpenVDB module (" + module.error +
        "); it must lie beside the toonwater program for .vdb files to be read");
  using Entry = const LevelSetModule* (*)();
  const LevelSetModule* loaded = reinterpret_cast<Entry>(module.entry)();
  if (!loaded || loaded->interface_version != level_set_module_interface_version)
    throw LevelSetModuleError(module.path.string() +
                              ": the OpenVDB module belongs to another build of toonwater");
  return loaded;
}

}  // namespace

const LevelSetModule& level_set_module() {
  static const LevelSetModule* module =
      load_level_set_module();  // thread-safe; retried after a failure
  return *module;
}

}  // namespace toonwater
