// image_codec() for programs linked with the codec itself (tests, benchmarks): see image_codec.hpp.
#include "images/image_codec.hpp"

namespace toonwater {

const ImageCodec& image_codec() { return *toonwater_image_codec_entry(); }

}  // namespace toonwater
