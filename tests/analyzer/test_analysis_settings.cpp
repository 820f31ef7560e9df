// The analysis settings' table (analyzer/analysis_settings.hpp) on its own: every setting
// reaches its field of the analyzer's options, the defaults are the analyzer's, and a range
// takes its ends and nothing past them.
#include "analyzer/analysis_settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace toonwater::test {
namespace {

TEST(AnalysisSettings, DefaultsAreTheAnalyzersOwn) {
  const AnalyzeOptions defaults;
  const AnalyzeOptions options = analyze_options(AnalysisSettings{}, Axis::z);
  EXPECT_EQ(options.flow.up, Axis::z);
  EXPECT_EQ(options.flow.criterion, defaults.flow.criterion);
  EXPECT_EQ(options.flow.threshold, defaults.flow.threshold);
  EXPECT_EQ(options.flow.threshold_relative, defaults.flow.threshold_relative);
  EXPECT_EQ(options.flow.smoothing_steps, defaults.flow.smoothing_steps);
  EXPECT_EQ(options.flow.min_region_area, defaults.flow.min_region_area);
  EXPECT_EQ(options.flow.rest_height, defaults.flow.rest_height);
  EXPECT_EQ(options.estimator, defaults.estimator);
  EXPECT_EQ(options.smoothing_steps, defaults.smoothing_steps);
  EXPECT_EQ(options.flow_regions, defaults.flow_regions);
}

TEST(AnalysisSettings, EverySettingReachesItsOption) {
  AnalysisSettings settings;
  // Through the table, each number a different value in its range.
  double next = 3;
  for (const AnalysisSetting& setting : analysis_settings()) {
    if (setting.is_word()) {
      setting.store_word(settings, setting.words.size() - 1);
    } else {
      ASSERT_EQ(setting.refusal(next), "") << setting.option;
      setting.store(settings, next++);
    }
  }
  const AnalyzeOptions options = analyze_options(settings, Axis::y);
  EXPECT_EQ(options.flow.criterion, FlowCriterion::paper);
  EXPECT_EQ(options.estimator, Estimator::jet);
  const std::set<double> numbers{*options.flow.threshold,
                                 *options.flow.threshold_relative,
                                 static_cast<double>(*options.flow.smoothing_steps),
                                 *options.flow.min_region_area,
                                 *options.flow.rest_height,
                                 static_cast<double>(options.smoothing_steps)};
  EXPECT_EQ(numbers.size(), 6u) << "two settings reach one option";
  EXPECT_EQ(*numbers.begin(), 3.0);
  EXPECT_EQ(*numbers.rbegin(), 8.0);
}

TEST(AnalysisSettings, ARangeTakesItsEndsAndNothingPast) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  for (const AnalysisSetting& setting : analysis_settings()) {
    if (setting.is_word()) continue;
    EXPECT_LT(setting.lo, setting.hi) << setting.option;
    EXPECT_EQ(setting.refusal(setting.lo), "") << setting.option;
    EXPECT_EQ(setting.refusal(setting.hi), "") << setting.option;
    EXPECT_NE(setting.refusal(std::nextafter(setting.lo, -inf)), "") << setting.option;
    EXPECT_NE(setting.refusal(std::nextafter(setting.hi, inf)), "") << setting.option;
    EXPECT_NE(setting.refusal(std::nan("")), "") << setting.option;
    EXPECT_EQ(setting.refusal(std::floor(setting.lo) + 0.5) == "must be a whole number",
              setting.is_whole_number())
        << setting.option;
  }
}

}  // namespace
}  // namespace toonwater::test
