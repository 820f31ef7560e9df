// The flow criteria compared; what is measured is stated in flow_study.hpp.
#include "report/flow_study.hpp"

#include "analyzer/disjoint_sets.hpp"
#include "analyzer/flow_regions.hpp"
#include "analyzer/mesh_reader.hpp"
#include "corpus/analytic_surfaces.hpp"
#include "pipeline/generate_scene.hpp"
#include "render/render.hpp"
#include "scene/scene_writer.hpp"
#include "pipeline/sequence.hpp"
#include "report/study_scene.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

namespace toonwater::report {
namespace {

namespace fs = std::filesystem;

constexpr double ripple_amplitude = 0.01, ripple_wavelength = 0.3;

double ripple_height(double x, double y) {
  const double r = std::hypot(x, y), k = 2 * std::numbers::pi / ripple_wavelength;
  const double inner = 2.0 * ripple_wavelength, outer = 2.8 * ripple_wavelength;
  const double fade = std::clamp((r - inner) / (outer - inner), 0.0, 1.0);
  const double envelope = std::pow(std::cos(0.5 * std::numbers::pi * fade), 2);
  return ripple_amplitude * std::cos(k * r) * envelope;
}

}  // namespace

TriangleMesh ripple_mesh(int n, double jitter) {
  TriangleMesh m = make_saddle(n, 1.0).mesh;  // an n × n grid over [−1, 1]², counter-clockwise
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> offset(-jitter, jitter);
  const double step = 2.0 / (n - 1);
  for (Vec3& p : m.positions) {
    if (jitter > 0 && std::abs(p.x()) < 1.0) p.x() += offset(rng) * step;
    if (jitter > 0 && std::abs(p.y()) < 1.0) p.y() += offset(rng) * step;
    p.z() = ripple_height(p.x(), p.y());
  }
  return m;
}

RippleCoverage ripple_coverage(const Analysis& a) {
  RippleCoverage c;
  std::size_t crest = 0, trough = 0, calm = 0;
  double labelled_area = 0, total_area = 0;
  for (std::size_t v = 0; v < a.surface.positions.size(); ++v) {
    const Vec3& p = a.surface.positions[v];
    const double phase = std::hypot(p.x(), p.y()) / ripple_wavelength;  // crests at whole numbers
    const std::int8_t label = a.flow.label[v];
    total_area += a.curvature.area[v];
    if (label != FlowLabel::none) labelled_area += a.curvature.area[v];
    if (phase > 3.0) {
      ++calm;
      c.calm_labelled += label != FlowLabel::none;
    }
    if (phase < 0.75 || phase > 2.0) continue;  // the dome at the centre, the fading envelope
    if (std::abs(phase - std::round(phase)) < 0.08) {
      ++crest;
      c.crest_ridge += label == FlowLabel::ridge;
    } else if (std::abs(phase - std::floor(phase) - 0.5) < 0.08) {
      ++trough;
      c.trough_valley += label == FlowLabel::valley;
    }
  }
  c.crest_ridge /= static_cast<double>(std::max<std::size_t>(crest, 1));
  c.trough_valley /= static_cast<double>(std::max<std::size_t>(trough, 1));
  c.calm_labelled /= static_cast<double>(std::max<std::size_t>(calm, 1));
  c.labelled_share = total_area > 0 ? labelled_area / total_area : 0.0;
  return c;
}

std::vector<RippleRow> run_ripple_study(const std::vector<int>& resolutions) {
  std::vector<RippleRow> rows;
  for (const FlowCriterion criterion : {FlowCriterion::mean, FlowCriterion::paper}) {
    AnalyzeOptions options;
    options.flow.up = Axis::z;
    options.flow.criterion = criterion;
    for (const bool jittered : {false, true})
      for (const int n : resolutions) {
        const Analysis a = analyze_mesh(ripple_mesh(n, jittered ? 0.3 : 0.0), options);
        rows.push_back(
            {criterion == FlowCriterion::mean ? "mean" : "paper", n, jittered, ripple_coverage(a)});
      }
  }
  return rows;
}

FlowMask flow_mask(const Image& image, const std::array<float, 3>& ridge,
                   const std::array<float, 3>& valley, float tolerance) {
  FlowMask mask{image.width, image.height,
                std::vector<std::int8_t>(static_cast<std::size_t>(image.width) * image.height, 0)};
  auto near = [&](const std::array<float, 3>& a, const std::array<float, 3>& b) {
    return std::abs(a[0] - b[0]) <= tolerance && std::abs(a[1] - b[1]) <= tolerance &&
           std::abs(a[2] - b[2]) <= tolerance;
  };
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto c = image.pixel(x, y);
      mask.classes[static_cast<std::size_t>(y) * image.width + x] = near(c, ridge)    ? 1
                                                                    : near(c, valley) ? -1
                                                                                      : 0;
    }
  return mask;
}

namespace {

// The length of the class boundaries, traced as marching squares through the pixel centres:
// per 2 × 2 block and class, a corner cut (one or three pixels of the class) is √2/2 long, a
// straight cut (two beside each other) 1, a saddle (two diagonal) two corners. A smooth curve
// gets its Euclidean length, a staircase the length of its steps.
double boundary_length(const FlowMask& m) {
  constexpr double corner = 0.70710678118654752;
  double length = 0.0;
  for (const std::int8_t cls : {std::int8_t{1}, std::int8_t{-1}})
    for (int y = 0; y + 1 < m.height; ++y)
      for (int x = 0; x + 1 < m.width; ++x) {
        auto in = [&](int dx, int dy) {
          return m.classes[static_cast<std::size_t>(y + dy) * m.width + x + dx] == cls;
        };
        const bool a = in(0, 0), b = in(1, 0), c = in(0, 1), d = in(1, 1);
        const int count = a + b + c + d;
        if (count == 1 || count == 3)
          length += corner;
        else if (count == 2)
          length += a == d ? 2 * corner : 1.0;  // a == d: the diagonal pair
      }
  return length;
}

// Each flow class blurred by a box `size` pixels wide and cut at one half.
FlowMask box_smoothed(const FlowMask& m, int size) {
  FlowMask out{m.width, m.height, std::vector<std::int8_t>(m.classes.size(), 0)};
  const int half = size / 2;
  for (const std::int8_t cls : {std::int8_t{1}, std::int8_t{-1}}) {
    // Summed-area table of the class's indicator.
    std::vector<std::int64_t> sum(static_cast<std::size_t>(m.width + 1) * (m.height + 1), 0);
    auto at = [&](int x, int y) -> std::int64_t& {
      return sum[static_cast<std::size_t>(y) * (m.width + 1) + x];
    };
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x)
        at(x + 1, y + 1) = at(x, y + 1) + at(x + 1, y) - at(x, y) +
                           (m.classes[static_cast<std::size_t>(y) * m.width + x] == cls);
    for (int y = 0; y < m.height; ++y)
      for (int x = 0; x < m.width; ++x) {
        const int x0 = std::max(0, x - half), x1 = std::min(m.width, x - half + size);
        const int y0 = std::max(0, y - half), y1 = std::min(m.height, y - half + size);
        const std::int64_t inside = at(x1, y1) - at(x0, y1) - at(x1, y0) + at(x0, y0);
        if (2 * inside > static_cast<std::int64_t>(x1 - x0) * (y1 - y0))
          out.classes[static_cast<std::size_t>(y) * m.width + x] = cls;
      }
  }
  return out;
}

}  // namespace

FlowPictureMetrics measure_flow_mask(const FlowMask& m, double pixels_per_cell) {
  FlowPictureMetrics metrics;
  const std::size_t n = m.classes.size();
  DisjointSets pieces(n);
  for (int y = 0; y < m.height; ++y)
    for (int x = 0; x < m.width; ++x) {
      const auto i = static_cast<std::int32_t>(y * m.width + x);
      if (m.classes[i] == 0) continue;
      ++metrics.flow_pixels;
      if (x + 1 < m.width && m.classes[i + 1] == m.classes[i]) pieces.join(i, i + 1);
      if (y + 1 < m.height && m.classes[i + m.width] == m.classes[i]) pieces.join(i, i + m.width);
    }
  if (metrics.flow_pixels == 0) return metrics;
  std::vector<std::size_t> piece_size(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    if (m.classes[i] != 0) ++piece_size[pieces.root(static_cast<std::int32_t>(i))];
  const double speck_pixels = 4.0 * pixels_per_cell * pixels_per_cell;
  std::size_t in_specks = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (m.classes[i] != 0 &&
        static_cast<double>(piece_size[pieces.root(static_cast<std::int32_t>(i))]) < speck_pixels)
      ++in_specks;
  metrics.speck_share = static_cast<double>(in_specks) / static_cast<double>(metrics.flow_pixels);
  const double smoothed =
      boundary_length(box_smoothed(m, std::max(1, static_cast<int>(std::lround(pixels_per_cell)))));
  metrics.boundary_ratio = smoothed > 0 ? boundary_length(m) / smoothed : 0.0;
  return metrics;
}

std::vector<SequenceFlowStudy> run_sequence_flow_study(const std::string& pattern, Axis up,
                                                       const fs::path& work_dir,
                                                       const fs::path& picture_dir,
                                                       double pixels_per_cell,
                                                       const std::vector<FlowCriterion>& criteria,
                                                       std::optional<FrameRange> frames) {
  Sequence sequence = find_sequence(pattern, fs::current_path());
  if (frames)
    std::erase_if(sequence.frames,
                  [&](const auto& f) { return f.first < frames->first || f.first > frames->last; });
  if (sequence.frames.empty()) throw InputError(pattern + ": no frame in the range");
  // The overhead camera and the picture size from the first frame: cells of the median edge.
  const TriangleMesh first = read_mesh(sequence.frames.begin()->second).mesh;
  Vec3 min = first.positions.front(), max = min;
  for (const Vec3& p : first.positions) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  const int u = up == Axis::x ? 1 : 0, v = up == Axis::z ? 1 : 2, w = static_cast<int>(up);
  const double cell = median_edge_length(first);
  const Vec3 centre = 0.5 * (min + max);
  const double across = max[u] - min[u], down = max[v] - min[v];
  const double height = 20.0 * std::max(across, down);
  Vec3 location = centre;
  location[w] = max[w] + height;
  location[v] -= 1e-4 * height;  // not exactly overhead: POV-Ray's sky vector must not be the view

  SceneConfig config;
  config.camera.location = location;
  config.camera.look_at = centre;
  config.camera.angle =
      2.0 * std::atan(0.5 * across / (height + max[w] - centre[w])) * 180.0 / std::numbers::pi;
  config.render.width = std::max(16, static_cast<int>(std::ceil(across / cell * pixels_per_cell)));
  config.render.height = std::max(16, static_cast<int>(std::ceil(down / cell * pixels_per_cell)));
  config.render.antialias = false;
  config.render.frames = frames;
  config.water.transmit = 0.0;
  config.water.reflection = 0.0;
  config.water.ks = 0.0;
  config.outline.enabled = false;
  const Color red{1, 0, 0}, green{0, 1, 0};
  config.flow.ridge_color = red;
  config.flow.valley_color = green;

  std::vector<SequenceFlowStudy> studies;
  for (const FlowCriterion criterion : criteria) {
    SequenceFlowStudy study;
    study.criterion = criterion == FlowCriterion::mean ? "mean" : "paper";
    config.flow.analysis.criterion = criterion;
    const fs::path scene_dir = work_dir / ("flow_" + study.criterion);
    write_and_render(config, pattern, up, scene_dir, "flow study");
    SceneLayout layout;
    layout.animation = sequence.frames.size() > 1;
    layout.last_frame = sequence.frames.rbegin()->first;
    std::vector<double> ratios;
    std::size_t flow_pixels = 0;
    double speck_pixels = 0;
    for (const auto& [frame, path] : sequence.frames) {
      const FlowMask mask =
          flow_mask(read_rgb(scene_dir / frame_image_name(layout, frame)), {1, 0, 0}, {0, 1, 0});
      const FlowPictureMetrics m = measure_flow_mask(mask, pixels_per_cell);
      ++study.frames;
      study.flow_pixels_by_frame[frame] = m.flow_pixels;
      if (m.flow_pixels == 0) continue;
      ++study.frames_with_regions;
      flow_pixels += m.flow_pixels;
      speck_pixels += m.speck_share * static_cast<double>(m.flow_pixels);
      if (m.boundary_ratio > 0) ratios.push_back(m.boundary_ratio);
    }
    study.speck_share = flow_pixels ? speck_pixels / static_cast<double>(flow_pixels) : 0.0;
    if (!ratios.empty()) {
      std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
      study.boundary_ratio = ratios[ratios.size() / 2];
    }
    auto middle = sequence.frames.begin();
    std::advance(middle, sequence.frames.size() / 2);
    study.picture = picture_dir / ("flow_" + study.criterion + ".png");
    fs::create_directories(picture_dir);
    fs::copy_file(scene_dir / frame_image_name(layout, middle->first), study.picture,
                  fs::copy_options::overwrite_existing);
    studies.push_back(std::move(study));
  }
  return studies;
}

}  // namespace toonwater::report
