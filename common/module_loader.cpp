// Modules loaded beside the program; stated in module_loader.hpp.
#include "common/module_loader.hpp"

#include <dlfcn.h>

#include <system_error>

namespace toonwater {

LoadedModule load_module_beside_program(const char* module_name, const char* entry_symbol) {
  LoadedModule loaded;
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error) {
    loaded.path = module_name;
    loaded.error =
        "cannot find the toonwater program's directory: /proc/self/exe: " + error.message();
    return loaded;
  }
  loaded.path = executable.parent_path() / module_name;
  void* module = dlopen(loaded.path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module) {
    loaded.error = dlerror();
    return loaded;
  }
  loaded.entry = dlsym(module, entry_symbol);
  if (!loaded.entry) loaded.error = std::string("no entry point ") + entry_symbol;
  return loaded;
}

}  // namespace toonwater
