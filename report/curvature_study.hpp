// Curvature error against run time: every estimator on analytic surfaces —
// sphere (icosphere), UV sphere (thin pole fans), torus, ellipsoid, saddle, height field — sampled
// regularly, with jittered vertices (moved within the surface by up to 0.2 of the grid step, an
// irregular triangulation) and with noise (moved off the surface in a random direction by up to 2%
// of the mean edge length, as marching-cubes output is), at several resolutions.
//
// Errors are over interior vertices, relative to the RMS of the exact value: RMS and maximum of
// |estimate − exact| / RMS(exact), for K and for H. Noisy meshes are compared with the exact
// values at the vertices before the noise. Time: the median over `repeats` runs of the
// curvature stage of analyze_mesh (estimator and smoothing), in seconds.
#pragma once

#include "analyzer/analysis.hpp"

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace toonwater::report {

struct Method {
  std::string name;  // as in the report and the CSV: "one-ring", "jet", "one-ring+smooth2"
  Estimator estimator;
  int smoothing_steps;
};

// The estimators the study compares.
const std::vector<Method>& study_methods();

extern const std::vector<std::string>
    study_surfaces;  // sphere, uv sphere, torus, ellipsoid, saddle, height field
extern const std::vector<std::string> study_samplings;  // regular, jittered, noisy

struct StudySample {
  std::string surface, sampling, method;
  std::size_t vertices = 0;
  double rms_gaussian = 0, max_gaussian = 0, rms_mean = 0, max_mean = 0;
  double seconds = 0;  // median
};

struct StudyOptions {
  std::vector<std::size_t> target_vertices;  // each surface is built as close to these as it allows
  int repeats = 3;
  std::function<void(const std::string&)> progress;  // one line per mesh, may be empty
};

std::vector<StudySample> run_curvature_study(const StudyOptions& options);

}  // namespace toonwater::report
