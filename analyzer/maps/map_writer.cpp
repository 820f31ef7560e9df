// Encodes the maps in memory with the image codec (images/image_codec.hpp) and hands the
// bytes to write_file_atomically, so every file appears complete or not at all.
//
// EXR compression: ZIP costs about 0.3 s on a 1024² seven-channel float map, too slow for the
// 0.2 s budget of a frame; RLE (lossless, fast) shrinks the large alpha-0 areas and constant
// runs of label and alpha. PNG previews use a low zlib level and no row filters for the same
// reason. The EXR is encoded on a second thread while the previews are drawn and encoded.
#include "analyzer/maps/map_writer.hpp"

#include "common/atomic_file.hpp"
#include "analyzer/maps/preview.hpp"

#include "images/image_codec.hpp"

#include <algorithm>
#include <array>
#include <future>
#include <cstdio>
#include <string_view>

namespace toonwater {
namespace fs = std::filesystem;
namespace {

constexpr const char* exr_compression = "rle";
constexpr int png_compression_level = 1;
constexpr int png_filter_none =
    0x08;  // libpng's PNG_FILTER_NONE: row filters cost more than they save here

const char* axis_name(Axis a) { return a == Axis::x ? "x" : a == Axis::y ? "y" : "z"; }

// "+x", "-z": the world axis a map axis runs along.
std::string axis_direction(const Vec3& d) {
  Eigen::Index k = 0;
  d.cwiseAbs().maxCoeff(&k);
  std::string name(1, d[k] > 0 ? '+' : '-');
  name += axis_name(static_cast<Axis>(k));
  return name;
}

std::string text(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

// All metadata is text: PNG keeps only text chunks, and the same reader code serves both.
std::vector<ImageText> metadata(const MapView& view, const MapRanges& ranges) {
  return {{"toonwater:K_range", text(ranges.gaussian)},
          {"toonwater:H_range", text(ranges.mean)},
          {"toonwater:up", axis_name(view.up)},
          {"toonwater:columns", axis_direction(map_u_axis(view.up))},
          {"toonwater:rows_down", axis_direction(-map_v_axis(view.up))},
          {"toonwater:box_uv", text(view.box.u_min) + " " + text(view.box.v_min) + " " +
                                   text(view.box.u_max) + " " + text(view.box.v_max)},
          {"toonwater:pixel_size", text(view.pixel_size)}};
}

void write_bytes(const fs::path& path, const std::vector<unsigned char>& bytes) {
  write_file_atomically(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

void write_exr(const ImageCodec& codec, const fs::path& path, const TopDownMap& map,
               const MapRanges& ranges) {
  FloatPlanes image;
  image.width = map.view.width;
  image.height = map.view.height;
  image.names = {"height", "K", "H", "k1", "k2", "label", "A"};
  image.planes = {map.height.data(), map.gaussian.data(), map.mean.data(), map.k1.data(),
                  map.k2.data(),     map.label.data(),    map.alpha.data()};
  image.alpha_channel = 6;
  std::vector<unsigned char> bytes;
  try {
    bytes = codec.encode_exr(image, metadata(map.view, ranges), exr_compression);
  } catch (const std::runtime_error& e) {
    throw OutputError("cannot encode " + path.string() + ": " + e.what());
  }
  write_bytes(path, bytes);
}

void write_png(const ImageCodec& codec, const fs::path& path, const PreviewImage& image,
               const MapView& view, const MapRanges& ranges, const std::string& description) {
  std::vector<ImageText> texts = metadata(view, ranges);
  texts.push_back({"ImageDescription", description});
  std::vector<unsigned char> bytes;
  try {
    bytes = codec.encode_png(image.width, image.height, image.rgb.data(), texts,
                             png_compression_level, png_filter_none);
  } catch (const std::runtime_error& e) {
    throw OutputError("cannot encode " + path.string() + ": " + e.what());
  }
  write_bytes(path, bytes);
}

}  // namespace

std::string frame_stem(const fs::path& frame) {
  fs::path stem = frame.stem();
  if (frame.extension() == ".gz") stem = stem.stem();
  return stem.string();
}

MapFiles map_files(const fs::path& dir, const std::string& stem) {
  return {dir / (stem + ".exr"), dir / (stem + "_K.png"), dir / (stem + "_H.png"),
          dir / (stem + "_label.png")};
}

MapFiles write_maps(const fs::path& dir, const std::string& stem, const TopDownMap& map,
                    const MapRanges& ranges) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw OutputError("cannot create " + dir.string() + ": " + error.message());
  const MapFiles files = map_files(dir, stem);
  const ImageCodec& codec = image_codec();
  // The thread's exception is carried out through the future.
  auto exr = std::async(std::launch::async, [&] { write_exr(codec, files.exr, map, ranges); });
  write_png(codec, files.gaussian_png, signed_preview(map, map.gaussian, ranges.gaussian, "K"),
            map.view, ranges, "Gaussian curvature K, top-down, diverging colours over +-K_range");
  write_png(codec, files.mean_png, signed_preview(map, map.mean, ranges.mean, "H"), map.view,
            ranges, "Mean curvature H, top-down, diverging colours over +-H_range");
  write_png(codec, files.label_png, label_preview(map), map.view, ranges,
            "Flow labels, top-down: valley, none, ridge");
  exr.get();
  return files;
}

MapFiles write_maps(const fs::path& dir, const std::string& stem, const Analysis& analysis,
                    const MapView& view, const MapRanges& ranges) {
  return write_maps(dir, stem,
                    rasterize_top_down(analysis.surface, analysis.curvature, analysis.flow.label,
                                       analysis.flow.free_surface, view),
                    ranges);
}

MapRanges write_frame_maps(const fs::path& dir, const std::string& stem, const Analysis& analysis,
                           Axis up, const MapOptions& options, MapFiles* files) {
  MapPlanner planner(up);
  planner.add(analysis);
  const MapRanges ranges = planner.ranges(options.percentile);
  const MapFiles written = write_maps(dir, stem, analysis, planner.view(options), ranges);
  if (files) *files = written;
  return ranges;
}

}  // namespace toonwater
