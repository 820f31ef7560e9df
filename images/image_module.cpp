// image_codec() for the toonwater program: loads toonwater-images.so from beside the program
// (common/module_loader.hpp) on first use, and keeps it loaded. See image_codec.hpp.
#include "images/image_codec.hpp"

#include "common/module_loader.hpp"

namespace toonwater {
namespace {

const ImageCodec* load_image_codec() {
  const LoadedModule module =
      load_module_beside_program("toonwater-images.so", "toonwater_image_codec_entry");
  if (!module.entry)
    throw ImageModuleError(module.path.string() + ": cannot load the image module (" +
                           module.error +
                           "); it must lie beside the toonwater program for images to be read "
                           "or written");
  using Entry = const ImageCodec* (*)();
  const ImageCodec* codec = reinterpret_cast<Entry>(module.entry)();
  if (!codec || codec->interface_version != image_codec_interface_version)
    throw ImageModuleError(module.path.string() +
                           ": the image module belongs to another build of toonwater");
  return codec;
}

}  // namespace

const ImageCodec& image_codec() {
  static const ImageCodec* codec = load_image_codec();  // thread-safe; retried after a failure
  return *codec;
}

}  // namespace toonwater
