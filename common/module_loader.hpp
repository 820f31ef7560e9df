// The modules the toonwater program loads from beside its executable on first use, so that a
// run that needs no heavy library does not pay for it: toonwater-images.so (OpenImageIO,
// images/image_codec.hpp) and toonwater-vdb.so (OpenVDB, analyzer/readers/vdb). Each exports
// one C entry point that returns its table of functions.
#pragma once

#include <filesystem>
#include <string>

namespace toonwater {

struct LoadedModule {
  std::filesystem::path path;  // where it was looked for
  void* entry = nullptr;       // the entry point's address; null, with `error` set, on failure
  std::string error;           // why it could not be loaded ("" on success)
};

// Loads `module_name` from the directory of the running executable (/proc/self/exe, so that a
// symbolic link to the program finds the real one) with RTLD_NOW | RTLD_LOCAL, and looks up
// `entry_symbol`. The module stays loaded.
LoadedModule load_module_beside_program(const char* module_name, const char* entry_symbol);

}  // namespace toonwater
