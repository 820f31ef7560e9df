#include "analyzer/analysis_settings.hpp"

#include "analyzer/flow_regions.hpp"

#include <charconv>
#include <cmath>
#include <type_traits>

namespace toonwater {

AnalyzeOptions analyze_options(const AnalysisSettings& settings, Axis up) {
  AnalyzeOptions options;
  options.flow.up = up;
  options.flow.criterion = settings.criterion;
  options.flow.threshold = settings.k_threshold;
  options.flow.threshold_relative = settings.k_threshold_relative;
  options.flow.smoothing_steps = settings.flow_smoothing;
  options.flow.min_region_area = settings.min_region;
  options.flow.rest_height = settings.rest_height;
  options.estimator = settings.estimator;
  options.smoothing_steps = settings.curvature_smoothing;
  return options;
}

std::string show_number(double value) {
  char buffer[32];
  return std::string(buffer, std::to_chars(buffer, buffer + sizeof buffer, value).ptr);
}

namespace {

// The type of the value a member pointer points to.
template <class Member>
struct member_value;
template <class T>
struct member_value<T AnalysisSettings::*> {
  using type = T;
};

}  // namespace

bool AnalysisSetting::is_word() const { return !words.empty(); }

bool AnalysisSetting::is_whole_number() const {
  return std::holds_alternative<std::optional<int> AnalysisSettings::*>(member) ||
         std::holds_alternative<int AnalysisSettings::*>(member);
}

std::string AnalysisSetting::refusal(double value) const {
  if (!std::isfinite(value)) return "must be finite";
  if (is_whole_number() && value != std::floor(value)) return "must be a whole number";
  if (value < lo || value > hi)
    return "must be between " + show_number(lo) + " and " + show_number(hi);
  return {};
}

std::string AnalysisSetting::type() const {
  if (is_word()) {
    std::string names;
    for (const auto& word : words) names += (names.empty() ? "\"" : " | \"") + word.first + "\"";
    return names;
  }
  return (is_whole_number() ? "whole number from " : "number from ") + show_number(lo) + " to " +
         show_number(hi);
}

void AnalysisSetting::store(AnalysisSettings& settings, double value) const {
  std::visit(
      [&](auto m) {
        using T = typename member_value<decltype(m)>::type;
        if constexpr (std::is_same_v<T, std::optional<double>>) settings.*m = value;
        if constexpr (std::is_same_v<T, std::optional<int>> || std::is_same_v<T, int>)
          settings.*m = static_cast<int>(value);
      },
      member);
}

void AnalysisSetting::store_word(AnalysisSettings& settings, std::size_t choice) const {
  std::visit(
      [&](auto m) {
        using T = typename member_value<decltype(m)>::type;
        if constexpr (std::is_enum_v<T>) settings.*m = static_cast<T>(words.at(choice).second);
      },
      member);
}

namespace {

using S = AnalysisSettings;

// A default that depends on the criterion, from flow_defaults: "2 (mean), 30 (paper)".
template <class Value>
std::string by_criterion(Value value) {
  const auto shown = [&](FlowCriterion c) { return value(flow_defaults(c)); };
  return shown(FlowCriterion::mean) + " (mean), " + shown(FlowCriterion::paper) + " (paper)";
}

std::vector<AnalysisSetting> make_settings() {
  const S defaults;
  const std::vector<std::pair<std::string, int>> criteria{
      {"mean", static_cast<int>(FlowCriterion::mean)},
      {"paper", static_cast<int>(FlowCriterion::paper)}};
  const std::vector<std::pair<std::string, int>> estimators{
      {"one-ring", static_cast<int>(Estimator::one_ring)},
      {"jet", static_cast<int>(Estimator::jet)}};
  const auto word_of = [](const std::vector<std::pair<std::string, int>>& words, auto value) {
    for (const auto& [word, v] : words)
      if (v == static_cast<int>(value)) return word;
    return std::string("?");
  };
  constexpr double positive = 1e-30, largest = 1e30, most_steps = 1000;
  return {
      {"criterion", "criterion", &S::criterion, 0, 0, criteria,
       word_of(criteria, defaults.criterion),
       "flow regions on the mean curvature H (crests and troughs, round ones included) or the "
       "paper's |K| with the sign of H"},
      {"k-threshold",
       "k_threshold",
       &S::k_threshold,
       positive,
       largest,
       {},
       "scene-relative",
       "absolute threshold T: on H (1/length) with mean, on |K| (1/length²) with paper; "
       "overrides the relative one"},
      {"k-threshold-relative",
       "k_threshold_relative",
       &S::k_threshold_relative,
       positive,
       largest,
       {},
       by_criterion([](const FlowDefaults& d) { return show_number(d.threshold_relative); }),
       "relative threshold: c in T = c/L (mean) or c/L² (paper), L the square root of the free "
       "surface's area"},
      {"flow-smooth",
       "smoothing",
       &S::flow_smoothing,
       0,
       most_steps,
       {},
       by_criterion([](const FlowDefaults& d) {
         return std::to_string(smoothing_steps_for_radius(d.smoothing_radius));
       }),
       "smoothing steps of the flow field over the free surface"},
      {"min-region",
       "min_region",
       &S::min_region,
       0,
       largest,
       {},
       by_criterion([](const FlowDefaults& d) {
         return d.min_region_relative > 0 ? show_number(d.min_region_relative) + " L²"
                                          : std::string("0");
       }),
       "smallest flow region drawn, in scene units²; smaller ones fade out"},
      {"rest-height",
       "rest_height",
       &S::rest_height,
       -largest,
       largest,
       {},
       "median height of the free surface",
       "water rest level along the up axis"},
      {"estimator", "estimator", &S::estimator, 0, 0, estimators,
       word_of(estimators, defaults.estimator),
       "curvature estimator: one-ring (the paper's operators, fastest) or jet (cubic fits over "
       "the two-ring: accurate on irregular and noisy meshes, slower)"},
      {"smooth",
       "curvature_smoothing",
       &S::curvature_smoothing,
       0,
       most_steps,
       {},
       std::to_string(defaults.curvature_smoothing),
       "steps of area-weighted smoothing of K and H over the one-ring"},
  };
}

}  // namespace

const std::vector<AnalysisSetting>& analysis_settings() {
  static const std::vector<AnalysisSetting> settings = make_settings();
  return settings;
}

}  // namespace toonwater
