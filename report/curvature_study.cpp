// Curvature error against run time; see curvature_study.hpp.
#include "report/curvature_study.hpp"

#include "corpus/analytic_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace toonwater::report {
namespace {

constexpr Jitter jitter{0.2, 7};
constexpr double noise_fraction = 0.02;  // of the mean edge length

AnalyticSurface make_surface(const std::string& surface, std::size_t target, Jitter j) {
  const double n = static_cast<double>(target);
  if (surface == "sphere" || surface == "ellipsoid") {
    // 10·4^s + 2 vertices.
    const int level =
        std::max(1, static_cast<int>(std::lround(std::log(n / 10.0) / std::log(4.0))));
    return surface == "sphere" ? make_icosphere(level, 1.0, j)
                               : make_ellipsoid(level, 1.0, 0.8, 0.6, j);
  }
  if (surface == "uv sphere") {  // rings × 2 rings
    const int rings = std::max(8, static_cast<int>(std::lround(std::sqrt(n / 2.0))));
    return make_uv_sphere(rings, 2 * rings, 1.0, j);
  }
  if (surface == "torus") {
    const int minor = std::max(8, static_cast<int>(std::lround(std::sqrt(n / 2.0))));
    return make_torus(2 * minor, minor, 1.0, 0.4, j);
  }
  const int side = std::max(9, static_cast<int>(std::lround(std::sqrt(n))));
  return surface == "saddle" ? make_saddle(side, 0.5, j) : make_wave_field(side, 0.1, 6.0, 1.0, j);
}

double mean_edge_length(const TriangleMesh& m) {
  double sum = 0.0;
  for (const Triangle& t : m.triangles)
    for (int c = 0; c < 3; ++c) sum += (m.positions[t[(c + 1) % 3]] - m.positions[t[c]]).norm();
  return m.triangles.empty() ? 0.0 : sum / (3.0 * static_cast<double>(m.triangles.size()));
}

void add_noise(TriangleMesh& m) {
  const double amplitude = noise_fraction * mean_edge_length(m);
  std::mt19937 engine(11);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (Vec3& p : m.positions) {
    Vec3 offset;
    do offset = Vec3(uniform(engine), uniform(engine), uniform(engine));
    while (offset.squaredNorm() > 1.0);  // uniform in the ball
    p += amplitude * offset;
  }
}

struct RelativeError {
  double rms = 0, max = 0;
};

RelativeError relative_error(const std::vector<double>& estimate, const Analysis& a,
                             const std::vector<double>& exact, const std::vector<bool>& interior) {
  double exact_sum = 0.0, error_sum = 0.0, error_max = 0.0;
  std::size_t count = 0;
  for (std::size_t v = 0; v < exact.size(); ++v) {
    if (!interior[v]) continue;
    const double error = std::abs(estimate[a.input_to_surface[v]] - exact[v]);
    exact_sum += exact[v] * exact[v];
    error_sum += error * error;
    error_max = std::max(error_max, error);
    ++count;
  }
  const double scale = std::sqrt(exact_sum / static_cast<double>(count));
  return {std::sqrt(error_sum / static_cast<double>(count)) / scale, error_max / scale};
}

}  // namespace

const std::vector<std::string> study_surfaces = {"sphere",    "uv sphere", "torus",
                                                 "ellipsoid", "saddle",    "height field"};
const std::vector<std::string> study_samplings = {"regular", "jittered", "noisy"};

const std::vector<Method>& study_methods() {
  static const std::vector<Method> methods = {
      {"one-ring", Estimator::one_ring, 0},
      {"one-ring+smooth2", Estimator::one_ring, 2},
      {"jet", Estimator::jet, 0},
      {"jet+smooth2", Estimator::jet, 2},
  };
  return methods;
}

std::vector<StudySample> run_curvature_study(const StudyOptions& options) {
  std::vector<StudySample> samples;
  const std::size_t meshes =
      study_surfaces.size() * study_samplings.size() * options.target_vertices.size();
  std::size_t done = 0;
  for (const std::string& surface : study_surfaces) {
    for (const std::string& sampling : study_samplings) {
      for (std::size_t target : options.target_vertices) {
        AnalyticSurface s =
            make_surface(surface, target, sampling == "jittered" ? jitter : Jitter{});
        if (sampling == "noisy") add_noise(s.mesh);
        if (options.progress)
          options.progress("[" + std::to_string(++done) + "/" + std::to_string(meshes) + "] " +
                           surface + ", " + sampling + ", " +
                           std::to_string(s.mesh.positions.size()) + " vertices");
        for (const Method& method : study_methods()) {
          AnalyzeOptions analyze;
          analyze.flow_regions = false;
          analyze.estimator = method.estimator;
          analyze.smoothing_steps = method.smoothing_steps;
          std::vector<double> seconds;
          Analysis a;
          for (int r = 0; r < std::max(1, options.repeats); ++r) {
            a = analyze_mesh(s.mesh, analyze);
            seconds.push_back(a.times.curvature);
          }
          std::nth_element(seconds.begin(), seconds.begin() + seconds.size() / 2, seconds.end());
          const RelativeError k = relative_error(a.curvature.gaussian, a, s.gaussian, s.interior);
          const RelativeError h = relative_error(a.curvature.mean, a, s.mean, s.interior);
          samples.push_back({surface, sampling, method.name, s.mesh.positions.size(), k.rms, k.max,
                             h.rms, h.max, seconds[seconds.size() / 2]});
        }
      }
    }
  }
  return samples;
}

}  // namespace toonwater::report
