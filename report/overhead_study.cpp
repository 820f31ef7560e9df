// Calm water from straight above; what is measured is stated in overhead_study.hpp.
#include "report/overhead_study.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "scene/scene_writer.hpp"
#include "pipeline/sequence.hpp"
#include "report/image.hpp"
#include "report/study_scene.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>
#include <stdexcept>

namespace toonwater::report {
namespace {

namespace fs = std::filesystem;

// The classes of a pixel, in the pure colours the scene draws them in.
enum Class : std::int8_t { other = -1, bright, medium, dark, ridge, valley };
constexpr std::array<Color, 5> kColours{{{1, 1, 0}, {0, 0, 1}, {0, 1, 1}, {1, 0, 0}, {0, 1, 0}}};

std::vector<std::int8_t> classify(const Image& image) {
  std::vector<std::int8_t> classes(static_cast<std::size_t>(image.width) * image.height, other);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto p = image.pixel(x, y);
      for (std::size_t c = 0; c < kColours.size(); ++c)
        if (std::abs(p[0] - kColours[c][0]) + std::abs(p[1] - kColours[c][1]) +
                std::abs(p[2] - kColours[c][2]) <
            0.1f)
          classes[static_cast<std::size_t>(y) * image.width + x] = static_cast<std::int8_t>(c);
    }
  return classes;
}

// The sizes of the 4-connected pieces of each class, per pixel (0 for `other`).
std::vector<std::size_t> piece_sizes(const std::vector<std::int8_t>& classes, int width) {
  const std::size_t n = classes.size();
  DisjointSets pieces = join_pieces<std::int8_t>(classes, width, other, false);
  std::vector<std::size_t> size(n, 0), of_pixel(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (classes[i] != other) ++size[pieces.root(static_cast<std::int32_t>(i))];
  for (std::size_t i = 0; i < n; ++i)
    if (classes[i] != other) of_pixel[i] = size[pieces.root(static_cast<std::int32_t>(i))];
  return of_pixel;
}

// The camera straight above the tank and the pure colours of a study's scene.
struct OverheadView {
  SceneConfig config;
  int u = 0, v = 1;          // the picture's horizontal and vertical input axes
  double pixel = 0;          // scene units a pixel
  double left = 0, top = 0;  // the picture's top-left corner, on axes u and v
};

OverheadView overhead_view(const OverheadOptions& options) {
  OverheadView view;
  const int w = static_cast<int>(options.up);
  const int u = w == 0 ? 1 : 0, v = w == 2 ? 1 : 2;
  view.u = u, view.v = v;
  const double across = options.tank_max[u] - options.tank_min[u];
  const double down = options.tank_max[v] - options.tank_min[v];
  // The tank and a margin of 2 % fill the picture; from 50 times its size away, a pixel is the
  // same size all over the water to 0.2 %.
  const double span = 1.04 * std::max(across, down * options.width / options.height);
  view.pixel = span / options.width;
  const double distance = 50.0 * span;
  Vec3 centre = 0.5 * (options.tank_min + options.tank_max);
  centre[w] = options.tank_max[w];
  Vec3 location = centre;
  location[w] += distance;
  location[v] -=
      1e-4 * distance;  // not exactly overhead: POV-Ray's sky vector must not be the view
  view.left = centre[u] - 0.5 * span;
  view.top = centre[v] + 0.5 * view.pixel * options.height;

  SceneConfig& config = view.config;
  config.camera.location = location;
  config.camera.look_at = centre;
  config.camera.angle = 2.0 * std::atan(0.5 * span / distance) * 180.0 / std::numbers::pi;
  config.render.width = options.width;
  config.render.height = options.height;
  config.render.antialias = false;
  config.render.frames = options.frames;
  config.render.background = {0, 0, 0};
  config.water.bright = kColours[bright];
  config.water.medium = kColours[medium];
  config.water.dark = kColours[dark];
  config.water.ka = 0.0;
  config.water.kd = 1.0;
  config.water.ks = 0.0;
  config.water.transmit = 0.0;
  config.water.reflection = 0.0;
  config.outline.enabled = false;
  config.flow.ridge_color = kColours[ridge];
  config.flow.valley_color = kColours[valley];
  for (const std::string& mesh : options.objects) {
    ObjectConfig object;
    object.name = "object" + std::to_string(config.objects.size());
    object.mesh = mesh;
    object.base_dir = fs::current_path();
    object.color = {1, 0, 1};
    object.outline = false;
    object.reflection = ReflectionTarget::none;
    config.objects.push_back(object);
  }
  return view;
}

// The rendered frames of `pattern` in `scene_dir`, within the options' range.
std::vector<std::pair<long, fs::path>> rendered_frames(const std::string& pattern,
                                                       const OverheadOptions& options,
                                                       const fs::path& scene_dir) {
  Sequence sequence = find_sequence(pattern, fs::current_path());
  if (options.frames)
    std::erase_if(sequence.frames, [&](const auto& f) {
      return f.first < options.frames->first || f.first > options.frames->last;
    });
  SceneLayout layout;
  layout.animation = sequence.frames.size() > 1;
  layout.last_frame = sequence.frames.rbegin()->first;
  std::vector<std::pair<long, fs::path>> frames;
  for (const auto& [frame, path] : sequence.frames)
    frames.emplace_back(frame, scene_dir / frame_image_name(layout, frame));
  return frames;
}

}  // namespace

std::vector<OverheadFrame> run_overhead_study(const std::string& pattern,
                                              const OverheadOptions& options,
                                              const fs::path& work_dir) {
  const OverheadView view = overhead_view(options);
  const SceneConfig& config = view.config;
  const int u = view.u, v = view.v;
  const double pixel = view.pixel;
  const fs::path scene_dir = work_dir / "overhead";
  write_and_render(config, pattern, options.up, scene_dir, "overhead study");

  const double cell_pixels = options.cell * options.cell / (pixel * pixel);
  const double left = view.left, top = view.top;
  std::vector<OverheadFrame> frames;
  std::vector<std::int8_t> previous;
  for (const auto& [frame, image_path] : rendered_frames(pattern, options, scene_dir)) {
    const Image image = read_rgb(image_path);
    const std::vector<std::int8_t> classes = classify(image);
    const std::vector<std::size_t> size = piece_sizes(classes, image.width);
    OverheadFrame f;
    f.frame = frame;
    std::size_t changed = 0, contrast = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const std::size_t i = static_cast<std::size_t>(y) * image.width + x;
        const std::int8_t c = classes[i];
        if (c == other) continue;
        ++f.water_pixels;
        contrast += c == bright || c == dark;
        if (!previous.empty() && previous[i] != other && previous[i] != c) ++changed;
        if (c == ridge || c == valley) {
          ++f.flow_pixels;
          const double px = left + (x + 0.5) * pixel, py = top - (y + 0.5) * pixel;
          const double to_wall = std::min({px - options.tank_min[u], options.tank_max[u] - px,
                                           py - options.tank_min[v], options.tank_max[v] - py});
          f.wall_flow_pixels += to_wall < 4.0 * options.cell;
        }
      }
    // Pieces counted once, at their root pixel's class: by the pixels over their size.
    double flow_pieces = 0, band_specks = 0;
    for (std::size_t i = 0; i < classes.size(); ++i) {
      const std::int8_t c = classes[i];
      if (c == other) continue;
      const double share = 1.0 / static_cast<double>(size[i]);
      if ((c == ridge || c == valley) && static_cast<double>(size[i]) >= cell_pixels)
        flow_pieces += share;
      if (c != ridge && c != valley && static_cast<double>(size[i]) < cell_pixels)
        band_specks += share;
    }
    f.flow_pieces = static_cast<std::size_t>(std::lround(flow_pieces));
    f.band_specks = static_cast<std::size_t>(std::lround(band_specks));
    f.changed_share =
        f.water_pixels ? static_cast<double>(changed) / static_cast<double>(f.water_pixels) : 0.0;
    f.contrast_share =
        f.water_pixels ? static_cast<double>(contrast) / static_cast<double>(f.water_pixels) : 0.0;
    frames.push_back(f);
    previous = classes;
  }
  return frames;
}

std::vector<StrokeFrame> run_stroke_study(const std::string& pattern,
                                          const OverheadOptions& options,
                                          const fs::path& work_dir) {
  constexpr int kReach = 2;  // pixels: a stroke pixel is kept when the next frame has one this near
  OverheadView view = overhead_view(options);
  // A stroke that moves with the water by up to a cell a frame is still there; one with no
  // stroke pixel within a cell in the next frame has gone.
  const int cell_reach = std::max(kReach, static_cast<int>(std::lround(options.cell / view.pixel)));
  SceneConfig& config = view.config;
  config.water.bright = config.water.medium = config.water.dark = {0.5, 0.5, 0.5};
  config.flow.style = FlowStyle::lines;
  config.flow.line_color = Color{1, 0, 0};
  const fs::path scene_dir = work_dir / "strokes";
  write_and_render(config, pattern, options.up, scene_dir, "stroke study");

  std::vector<StrokeFrame> frames;
  std::vector<std::uint8_t> previous;  // the last frame's stroke pixels
  int width = 0, height = 0;
  for (const auto& [frame, image_path] : rendered_frames(pattern, options, scene_dir)) {
    const Image image = read_rgb(image_path);
    width = image.width, height = image.height;
    std::vector<std::uint8_t> stroke(static_cast<std::size_t>(width) * height, 0);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const auto p = image.pixel(x, y);
        stroke[static_cast<std::size_t>(y) * width + x] =
            std::abs(p[0] - 1.0f) + p[1] + p[2] < 0.1f;
      }
    if (!frames.empty() && frames.back().stroke_pixels > 0) {
      const auto pixels = static_cast<double>(frames.back().stroke_pixels);
      frames.back().lost_share =
          static_cast<double>(pixels_without_neighbour(previous, stroke, width, kReach)) / pixels;
      frames.back().gone_share =
          static_cast<double>(pixels_without_neighbour(previous, stroke, width, cell_reach)) /
          pixels;
    }
    StrokeFrame f;
    f.frame = frame;
    // The strokes the scene draws: the Toon_stroke calls of the frame's water include.
    std::ifstream file(scene_dir / water_include_name(frame));
    if (!file) throw std::runtime_error("stroke study: cannot read " + water_include_name(frame));
    const std::string include{std::istreambuf_iterator<char>(file), {}};
    for (std::size_t at = include.find("Toon_stroke("); at != std::string::npos;
         at = include.find("Toon_stroke(", at + 1))
      ++f.strokes;
    f.stroke_pixels = static_cast<std::size_t>(std::count(stroke.begin(), stroke.end(), 1));
    f.stroke_pieces = pieces_of(stroke, width);
    frames.push_back(f);
    previous = std::move(stroke);
  }
  return frames;
}

}  // namespace toonwater::report
