// The analysis settings (analyzer/analysis_settings.hpp) through both front ends: every setting
// is a `toonwater analyze` option and a [flow] key of scene.toml with the same range and
// default; a value given to either gives the same analysis; a value out of range is refused by
// both, in the same words.
#include "analyzer/analysis_settings.hpp"
#include "scene/config.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// `toonwater analyze --help`'s entry of --`option`: from its name to the next option's.
std::string help_entry(const std::string& help, const std::string& option) {
  const std::size_t at = help.find("\n  --" + option + " ");
  if (at == std::string::npos) return "";
  return help.substr(at + 1, help.find("\n  -", at + 1) - at - 1);
}

const ConfigKey* scene_key(const std::vector<ConfigKey>& keys, const std::string& key) {
  for (const ConfigKey& k : keys)
    if (k.key == key) return &k;
  return nullptr;
}

TEST(AnalysisOptions, EverySettingIsAnOptionAndAKeyWithOneRangeAndDefault) {
  const CommandResult help = run_toonwater({"analyze", "--help"});
  ASSERT_EQ(help.exit_code, 0) << help.output;
  const std::vector<ConfigKey> keys = config_keys();
  for (const AnalysisSetting& setting : analysis_settings()) {
    const std::string entry = help_entry(help.output, setting.option);
    ASSERT_FALSE(entry.empty()) << "no --" << setting.option << " in analyze --help";
    const ConfigKey* key = scene_key(keys, "flow." + setting.key);
    ASSERT_NE(key, nullptr) << "no scene key flow." << setting.key;
    if (setting.is_word()) {
      for (const auto& [word, value] : setting.words) {
        EXPECT_TRUE(has(entry, word)) << entry;
        EXPECT_TRUE(has(key->type, "\"" + word + "\"")) << key->type;
      }
      EXPECT_TRUE(has(entry, "=" + setting.default_value)) << entry;
      EXPECT_EQ(key->default_value, "\"" + setting.default_value + "\"");
    } else {
      EXPECT_TRUE(has(entry, setting.type())) << entry;
      EXPECT_EQ(key->type, setting.type());
      EXPECT_TRUE(has(entry, "=" + setting.default_value) ||
                  has(entry, "(default: " + setting.default_value + ")"))
          << entry;
      EXPECT_EQ(key->default_value, setting.default_value);
    }
  }
}

// What analyze takes that is not a setting of the analysis: where the mesh comes from and where
// the results go.
const std::set<std::string> input_and_output_options{"help", "transform",  "scale",    "translate",
                                                     "grid", "adaptivity", "csv",      "ply",
                                                     "maps", "maps-size",  "maps-box", "up"};

TEST(AnalysisOptions, EveryOtherAnalyzeOptionIsAboutInputOrOutput) {
  const CommandResult help = run_toonwater({"analyze", "--help"});
  ASSERT_EQ(help.exit_code, 0) << help.output;
  std::set<std::string> settings;
  for (const AnalysisSetting& setting : analysis_settings()) settings.insert(setting.option);
  const std::regex option_name(R"(\n  (?:-h,)?--([a-z0-9-]+))");
  std::size_t options = 0;
  for (auto it = std::sregex_iterator(help.output.begin(), help.output.end(), option_name);
       it != std::sregex_iterator(); ++it, ++options) {
    const std::string name = (*it)[1];
    EXPECT_TRUE(settings.count(name) || input_and_output_options.count(name))
        << "--" << name << " is neither an analysis setting nor input or output";
  }
  EXPECT_EQ(options, settings.size() + input_and_output_options.size());
}

// A 2.4 x 2.4 ripple ring (y up), and 0.5 x 0.5 of waves 1 below it: a second free-surface
// patch, dropped below the rest level the large one gives.
std::string water_obj() {
  std::ostringstream obj;
  int vertices = 0;
  const auto grid = [&](int n, double spacing, double x0, double y0,
                        double (*height)(double x, double z)) {
    const int first = vertices + 1;
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = x0 + i * spacing, z = j * spacing;
        obj << "v " << x << ' ' << y0 + height(x - x0, z) << ' ' << z << '\n';
        ++vertices;
      }
    for (int j = 0; j + 1 < n; ++j)
      for (int i = 0; i + 1 < n; ++i) {
        const int a = first + j * n + i, b = a + 1, c = a + n, d = c + 1;
        obj << "f " << a << ' ' << c << ' ' << b << "\nf " << b << ' ' << c << ' ' << d << '\n';
      }
  };
  grid(25, 0.1, 0.0, 0.0, [](double x, double z) {
    const double r = std::hypot(x - 1.2, z - 1.2);
    return 0.04 * std::cos(9.0 * r) * std::exp(-r);
  });
  grid(6, 0.1, 4.0, -1.0, [](double x, double z) { return 0.02 * std::sin(12.0 * x + 7.0 * z); });
  return obj.str();
}

// A value of each setting other than its default, that changes the analysis of water_obj().
const std::map<std::string, std::string> changed_value{
    {"k-threshold", "0.5"}, {"k-threshold-relative", "1"}, {"flow-smooth", "6"},
    {"min-region", "1"},    {"rest-height", "-1"},         {"smooth", "3"}};

std::string value_to_try(const AnalysisSetting& setting) {
  if (setting.is_word())
    for (const auto& [word, value] : setting.words)
      if (word != setting.default_value) return word;
  const auto found = changed_value.find(setting.option);
  return found == changed_value.end() ? "" : found->second;
}

// The flow field s per vertex of an analyze CSV, sorted.
std::vector<double> csv_field(const std::string& csv) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::size_t column = std::count(line.begin(), line.begin() + line.find("flow"), ',');
  std::vector<double> field;
  while (std::getline(in, line)) {
    std::istringstream cells(line);
    std::string cell;
    for (std::size_t c = 0; c <= column; ++c) std::getline(cells, cell, ',');
    field.push_back(std::stod(cell));
  }
  std::sort(field.begin(), field.end());
  return field;
}

// The texture coordinate v the scene gives a vertex of field s (povgen/scene_mesh.hpp).
double flow_coordinate(double s) { return 0.5 + 0.12 * std::clamp(s, -4.0, 4.0); }

// The v of every uv of the scene's water mesh2, sorted.
std::vector<double> scene_flow_coordinates(const std::string& inc) {
  const std::size_t begin = inc.find("uv_vectors");
  const std::string block = inc.substr(begin, inc.find('}', begin) - begin);
  const std::regex uv(R"(<([-0-9.e]+),([-0-9.e]+)>)");
  std::vector<double> v;
  for (auto it = std::sregex_iterator(block.begin(), block.end(), uv); it != std::sregex_iterator();
       ++it)
    v.push_back(std::stod((*it)[2]));
  std::sort(v.begin(), v.end());
  return v;
}

class SameAnalysis : public ::testing::Test {
 protected:
  void SetUp() override { write_text(dir / "w.obj", water_obj()); }

  // The flow field's texture coordinates as analyze's CSV gives them (`option` = `value`).
  std::vector<double> analyzed(const std::string& option, const std::string& value) {
    const std::string csv = (dir / ("a" + std::to_string(runs) + ".csv")).string();
    std::vector<std::string> args{"analyze", (dir / "w.obj").string(), "--csv", csv};
    if (!option.empty()) args.insert(args.end(), {"--" + option, value});
    const CommandResult r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    std::vector<double> v = csv_field(read_text(csv));
    for (double& s : v) s = flow_coordinate(s);
    ++runs;
    return v;
  }

  // The same as povgen writes them into the scene (`key` = `value`).
  std::vector<double> scene(const std::string& key, const std::string& value) {
    const std::string out = (dir / ("scene" + std::to_string(runs))).string();
    std::vector<std::string> args{"povgen", "--water", (dir / "w.obj").string(), "--out", out,
                                  // the full mesh, every patch: one uv per vertex analysed
                                  "--set", "water.simplify=0", "--set", "water.min_patch=0"};
    if (!key.empty()) args.insert(args.end(), {"--set", "flow." + key + "=" + value});
    const CommandResult r = run_toonwater(args);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    ++runs;
    return scene_flow_coordinates(read_text(out + "/water_0000.inc"));
  }

  ScratchDir dir;
  int runs = 0;
};

// Written with 6 decimals from a float: within 1e-6 of the double.
void expect_same(const std::vector<double>& a, const std::vector<double>& b,
                 const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  double largest = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  EXPECT_LT(largest, 1e-6) << what;
}

bool differ(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return true;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-4) return true;
  return false;
}

TEST_F(SameAnalysis, AnOptionAndItsSceneKeyGiveTheSameFlowField) {
  const std::vector<double> by_default = analyzed("", "");
  expect_same(by_default, scene("", ""), "defaults");
  for (const AnalysisSetting& setting : analysis_settings()) {
    const std::string value = value_to_try(setting);
    ASSERT_FALSE(value.empty()) << "no value to try for --" << setting.option;
    const std::vector<double> analyze_field = analyzed(setting.option, value);
    EXPECT_TRUE(differ(analyze_field, by_default))
        << "--" << setting.option << " " << value << " changes nothing on this water";
    expect_same(analyze_field, scene(setting.key, value),
                "--" + setting.option + " " + value + " and flow." + setting.key + " = " + value);
  }
}

// `povgen --set flow.KEY=VALUE` and `analyze --OPTION VALUE`.
CommandResult scene_with(const ScratchDir& dir, const std::string& key, const std::string& value) {
  return run_toonwater({"povgen", "--water", (dir / "w.obj").string(), "--out",
                        (dir / "scene").string(), "--force", "--set", "flow." + key + "=" + value});
}
CommandResult analyze_with(const ScratchDir& dir, const std::string& option,
                           const std::string& value) {
  return run_toonwater({"analyze", (dir / "w.obj").string(), "--" + option, value});
}

TEST(AnalysisOptions, BothFrontEndsRefuseAValueOutOfRangeInTheSameWords) {
  ScratchDir dir;
  write_text(dir / "w.obj", water_obj());
  for (const AnalysisSetting& setting : analysis_settings()) {
    std::vector<double> refused{setting.lo > 0    ? 0.0
                                : setting.lo == 0 ? -1.0
                                                  : 10 * setting.lo,
                                setting.hi == 1000 ? 1001 : 10 * setting.hi};
    if (setting.is_whole_number()) refused.push_back(2.5);
    if (setting.is_word()) refused.clear();
    for (const double value : refused) {
      char text[32];
      std::snprintf(text, sizeof text, "%.17g", value);
      const std::string why = setting.refusal(value);
      ASSERT_TRUE(why.rfind("must be ", 0) == 0) << setting.option << " " << text << ": " << why;
      const CommandResult cli = analyze_with(dir, setting.option, text);
      EXPECT_EQ(cli.exit_code, 2) << cli.output;
      EXPECT_TRUE(has(cli.output, "--" + setting.option + ": '" + text + "' " + why)) << cli.output;
      const CommandResult scene = scene_with(dir, setting.key, text);
      EXPECT_EQ(scene.exit_code, 2) << scene.output;
      EXPECT_TRUE(has(scene.output, "'flow." + setting.key + "' " + why)) << scene.output;
    }
    if (setting.is_word()) {
      const CommandResult cli = analyze_with(dir, setting.option, "nonsense");
      const CommandResult scene = scene_with(dir, setting.key, "nonsense");
      EXPECT_EQ(cli.exit_code, 2) << cli.output;
      EXPECT_EQ(scene.exit_code, 2) << scene.output;
      EXPECT_TRUE(has(cli.output, "--" + setting.option)) << cli.output;
      EXPECT_TRUE(has(scene.output, "'flow." + setting.key + "'")) << scene.output;
      for (const auto& [word, enum_value] : setting.words) {
        EXPECT_TRUE(has(cli.output, word)) << cli.output;
        EXPECT_TRUE(has(scene.output, word)) << scene.output;
      }
    }
  }
  // The top of the flow field's smoothing range, taken by both.
  EXPECT_EQ(analyze_with(dir, "flow-smooth", "1000").exit_code, 0);
  EXPECT_EQ(scene_with(dir, "smoothing", "1000").exit_code, 0);
}

}  // namespace
}  // namespace toonwater::test
