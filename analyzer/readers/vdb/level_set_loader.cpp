// level_set_module() for the toonwater program: loads toonwater-vdb.so from the directory of the
// running executable on first use, and keeps it loaded. See level_set_module.hpp.
#include "analyzer/readers/vdb/level_set_module.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

namespace toonwater {
namespace {

constexpr const char* module_name = "toonwater-vdb.so";

const LevelSetModule* load_level_set_module() {
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error)
    throw LevelSetModuleError(std::string("cannot find the toonwater program's directory to load ") +
                              module_name + ": /proc/self/exe: " + error.message());
  const std::filesystem::path path = executable.parent_path() / module_name;
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module)
    throw LevelSetModuleError(path.string() + ": cannot load the OpenVDB module (" + dlerror() +
                              "); it must lie beside the toonwater program for .vdb files to be read");
  using Entry = const LevelSetModule* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(module, "toonwater_level_set_module_entry"));
  const LevelSetModule* loaded = entry ? entry() : nullptr;
  if (!loaded || loaded->interface_version != level_set_module_interface_version)
    throw LevelSetModuleError(path.string() + ": the OpenVDB module belongs to another build of toonwater");
  return loaded;
}

}  // namespace

const LevelSetModule& level_set_module() {
  static const LevelSetModule* module = load_level_set_module();  // thread-safe; retried after a failure
  return *module;
}

}  // namespace toonwater
