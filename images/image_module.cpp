// image_codec() for the toonwater program: loads toonwater-images.so from the directory of the
// running executable (/proc/self/exe, so a symbolic link to the program finds the real one) on
// first use, and keeps it loaded. See image_codec.hpp.
#include "images/image_codec.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

namespace toonwater {
namespace {

constexpr const char* module_name = "toonwater-images.so";

const ImageCodec* load_image_codec() {
  std::error_code error;
  const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", error);
  if (error)
    throw ImageModuleError(std::string("cannot find the toonwater program's directory to load ") +
                           module_name + ": /proc/self/exe: " + error.message());
  const std::filesystem::path path = executable.parent_path() / module_name;
  void* module = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!module)
    throw ImageModuleError(path.string() + ": cannot load the image module (" + dlerror() +
                           "); it must lie beside the toonwater program for images to be read "
                           "or written");
  using Entry = const ImageCodec* (*)();
  const auto entry = reinterpret_cast<Entry>(dlsym(module, "toonwater_image_codec_entry"));
  const ImageCodec* codec = entry ? entry() : nullptr;
  if (!codec || codec->interface_version != image_codec_interface_version)
    throw ImageModuleError(path.string() +
                           ": the image module belongs to another build of toonwater");
  return codec;
}

}  // namespace

const ImageCodec& image_codec() {
  static const ImageCodec* codec = load_image_codec();  // thread-safe; retried after a failure
  return *codec;
}

}  // namespace toonwater
