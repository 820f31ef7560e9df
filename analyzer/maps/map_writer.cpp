// Encodes the maps in memory with OpenImageIO (an IOProxy instead of a file) and hands the
// bytes to write_file_atomically, so every file appears complete or not at all.
//
// EXR compression: ZIP costs about 0.3 s on a 1024² seven-channel float map, too slow for the
// 0.2 s budget of a frame; RLE (lossless, fast) shrinks the large alpha-0 areas and constant
// runs of label and alpha. PNG previews use a low zlib level and no row filters for the same
// reason. The EXR is encoded on a second thread while the previews are drawn and encoded.
#include "analyzer/maps/map_writer.hpp"

#include "analyzer/atomic_file.hpp"
#include "analyzer/maps/preview.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

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
constexpr int png_filter_none = 0x08;  // libpng's PNG_FILTER_NONE: row filters cost more than they save here

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
void add_metadata(OIIO::ImageSpec& spec, const MapView& view, const MapRanges& ranges) {
  spec.attribute("toonwater:K_range", text(ranges.gaussian));
  spec.attribute("toonwater:H_range", text(ranges.mean));
  spec.attribute("toonwater:up", axis_name(view.up));
  spec.attribute("toonwater:columns", axis_direction(map_u_axis(view.up)));
  spec.attribute("toonwater:rows_down", axis_direction(-map_v_axis(view.up)));
  spec.attribute("toonwater:box_uv", text(view.box.u_min) + " " + text(view.box.v_min) + " " +
                                         text(view.box.u_max) + " " + text(view.box.v_max));
  spec.attribute("toonwater:pixel_size", text(view.pixel_size));
}

std::vector<unsigned char> encode(const char* format, const OIIO::ImageSpec& spec,
                                  OIIO::TypeDesc type, const void* pixels,
                                  const fs::path& path) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create(format);
  if (!out || !out->set_ioproxy(&memory) || !out->open(path.string(), spec) ||
      !out->write_image(type, pixels) || !out->close())
    throw OutputError("cannot encode " + path.string() + ": " +
                      (out ? out->geterror() : OIIO::geterror()));
  return bytes;
}

void write_exr(const fs::path& path, const TopDownMap& map, const MapRanges& ranges) {
  const std::array<const std::vector<float>*, 7> channels{
      &map.height, &map.gaussian, &map.mean, &map.k1, &map.k2, &map.label, &map.alpha};
  const int width = map.view.width, height = map.view.height;
  OIIO::ImageSpec spec(width, height, static_cast<int>(channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"height", "K", "H", "k1", "k2", "label", "A"};
  spec.alpha_channel = 6;
  spec.attribute("compression", exr_compression);
  add_metadata(spec, map.view, ranges);

  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput memory(bytes);
  auto out = OIIO::ImageOutput::create("openexr");
  bool ok = out && out->set_ioproxy(&memory) && out->open(path.string(), spec);
  // Interleaved a band of rows at a time, so no second copy of the whole map is made.
  constexpr int band_rows = 32;
  std::vector<float> band(static_cast<std::size_t>(band_rows) * width * channels.size());
  for (int y0 = 0; ok && y0 < height; y0 += band_rows) {
    const int y1 = std::min(height, y0 + band_rows);
    const std::size_t first = static_cast<std::size_t>(y0) * width;
    const std::size_t count = static_cast<std::size_t>(y1 - y0) * width;
    for (std::size_t i = 0; i < count; ++i)
      for (std::size_t c = 0; c < channels.size(); ++c)
        band[i * channels.size() + c] = (*channels[c])[first + i];
    ok = out->write_scanlines(y0, y1, 0, OIIO::TypeDesc::FLOAT, band.data());
  }
  if (!ok || !out->close())
    throw OutputError("cannot encode " + path.string() + ": " +
                      (out ? out->geterror() : OIIO::geterror()));
  write_file_atomically(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

void write_png(const fs::path& path, const PreviewImage& image, const MapView& view,
               const MapRanges& ranges, const std::string& description) {
  OIIO::ImageSpec spec(image.width, image.height, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("png:compressionLevel", png_compression_level);
  spec.attribute("png:filter", png_filter_none);
  spec.attribute("ImageDescription", description);
  add_metadata(spec, view, ranges);
  const auto bytes = encode("png", spec, OIIO::TypeDesc::UINT8, image.rgb.data(), path);
  write_file_atomically(path, {reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

}  // namespace

MapFiles write_maps(const fs::path& dir, const std::string& stem, const TopDownMap& map,
                    const MapRanges& ranges) {
  std::error_code error;
  fs::create_directories(dir, error);
  if (error) throw OutputError("cannot create " + dir.string() + ": " + error.message());
  MapFiles files{dir / (stem + ".exr"), dir / (stem + "_K.png"), dir / (stem + "_H.png"),
                 dir / (stem + "_label.png")};
  // The thread's exception is carried out through the future.
  auto exr = std::async(std::launch::async, [&] { write_exr(files.exr, map, ranges); });
  write_png(files.gaussian_png, signed_preview(map, map.gaussian, ranges.gaussian, "K"), map.view,
            ranges, "Gaussian curvature K, top-down, diverging colours over +-K_range");
  write_png(files.mean_png, signed_preview(map, map.mean, ranges.mean, "H"), map.view, ranges,
            "Mean curvature H, top-down, diverging colours over +-H_range");
  write_png(files.label_png, label_preview(map), map.view, ranges,
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
