// The analysis settings: what a user can change about an analysis, as one table. Each setting
// has its `toonwater analyze` option (--flow-smooth), its scene.toml key in [flow]
// (flow.smoothing), its range, its default and a line of help, written here once. The analyze
// command (cli/analysis_options.hpp) and the scene configuration (scene/config_schema.cpp) are
// both made from the table, so a scene can repeat any analyze run, and both front ends take the
// same values and refuse the others with the same words.
//
// Ranges, ends included: smoothing steps 0-1000 (1000 Jacobi steps spread a field over about
// 18 edge lengths, past any feature worth a region); thresholds 1e-30-1e30 and areas 0-1e30;
// the rest height ±1e30 (a double holds more, no scene is that large).
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace toonwater {

// The settings' values. The defaults are the analyzer's own (AnalyzeOptions); unset optionals
// take the criterion's (flow_defaults) or, for the rest height, the free surface's
// (free_surface.hpp).
struct AnalysisSettings {
  FlowCriterion criterion = FlowOptions{}.criterion;
  std::optional<double> k_threshold;           // absolute T: 1/length (mean), 1/length² (paper)
  std::optional<double> k_threshold_relative;  // c in T = c / L or c / L²
  std::optional<int> flow_smoothing;           // smoothing steps of the flow field
  std::optional<double> min_region;            // A_min in scene units²
  std::optional<double> rest_height;           // along the up axis
  Estimator estimator = AnalyzeOptions{}.estimator;
  int curvature_smoothing = AnalyzeOptions{}.smoothing_steps;  // smoothing steps of K and H
};

// The analyzer's options for `settings` on a mesh whose up axis is `up`.
AnalyzeOptions analyze_options(const AnalysisSettings& settings, Axis up);

// Where a setting's value is kept; its type says how the value is given: a word (an enum), a
// number (double) or a whole number (int).
using SettingMember = std::variant<FlowCriterion AnalysisSettings::*, Estimator AnalysisSettings::*,
                                   std::optional<double> AnalysisSettings::*,
                                   std::optional<int> AnalysisSettings::*, int AnalysisSettings::*>;

struct AnalysisSetting {
  std::string option;  // "flow-smooth": `toonwater analyze --flow-smooth`
  std::string key;     // "smoothing": scene.toml's flow.smoothing
  SettingMember member;
  double lo = 0.0, hi = 0.0;                       // a number's range, ends included
  std::vector<std::pair<std::string, int>> words;  // a word's choices and their enum values
  std::string default_value;  // as shown: "mean", "0", "2 (mean), 0 (paper)", or what decides it
  std::string help;           // one line, lower case

  bool is_word() const;
  bool is_whole_number() const;
  // "" when `value` is taken, else why not, as both front ends say it after the option's or
  // key's name: "must be a whole number", "must be between 0 and 1000".
  std::string refusal(double value) const;
  // What the setting takes: "whole number from 0 to 1000", "\"mean\" | \"paper\"".
  std::string type() const;
  // Keeps `value`, which refusal() took, or words[choice] for a word.
  void store(AnalysisSettings& settings, double value) const;
  void store_word(AnalysisSettings& settings, std::size_t choice) const;
};

// Every setting, in the order of the analyze command's help and of the [flow] table.
const std::vector<AnalysisSetting>& analysis_settings();

// Shortest text that reads back as the same double: 0.002, 30, -1, 1e+30.
std::string show_number(double value);

}  // namespace toonwater
