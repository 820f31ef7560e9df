// The configuration's schema (scene/config_schema.hpp) against its documentation and its own
// rules: docs/scenes.md's key table lists every key, in the schema's order, with the schema's
// default; integer keys take whole numbers only, and a bad value in a file names file and line;
// the config fuzzer's dictionary (tests/fuzz/config.dict) names every table and key.
#include "scene/config.hpp"
#include "tests/support/scene_config.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace toonwater::test {
namespace {

struct Row {
  std::vector<std::string> keys;  // "water.bright", "water.medium", ... for `water.bright` `medium`
  std::string default_value;
};

// The cells of a Markdown table row; "\|" inside a cell is not a separator.
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|' && line[i - 1] != '\\') {
      const auto first = cell.find_first_not_of(' ');
      const auto last = cell.find_last_not_of(' ');
      out.push_back(first == std::string::npos ? "" : cell.substr(first, last - first + 1));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return out;
}

// The rows of the table under "| key | default | meaning |".
std::vector<Row> documented_keys(const std::string& readme) {
  std::vector<Row> rows;
  const std::size_t table = readme.find("| key | default | meaning |");
  if (table == std::string::npos) return rows;
  std::size_t at = readme.find('\n', readme.find('\n', table) + 1) + 1;  // past the rule line
  while (at < readme.size() && readme[at] == '|') {
    const std::size_t end = readme.find('\n', at);
    const std::vector<std::string> row = cells(readme.substr(at, end - at));
    at = end + 1;
    if (row.size() != 3) {
      ADD_FAILURE() << "a row of " << row.size() << " cells: " << row[0];
      continue;
    }
    Row r;
    r.default_value = row[1];
    std::string section;
    for (std::size_t open = row[0].find('`'); open != std::string::npos;) {
      const std::size_t close = row[0].find('`', open + 1);
      std::string name = row[0].substr(open + 1, close - open - 1);
      if (name.rfind("[[object]] ", 0) == 0) name = "object." + name.substr(11);
      if (const std::size_t dot = name.find('.'); dot != std::string::npos)
        section = name.substr(0, dot);
      else
        name = section + "." + name;
      r.keys.push_back(name);
      open = row[0].find('`', close + 1);
    }
    rows.push_back(r);
  }
  return rows;
}

TEST(ConfigSchema, TheReadmeTableListsEveryKeyWithItsDefault) {
  const std::vector<Row> rows =
      documented_keys(read_text(std::string(TOONWATER_SOURCE_DIR) + "/docs/scenes.md"));
  ASSERT_FALSE(rows.empty()) << "no key table in docs/scenes.md";
  const std::vector<ConfigKey> schema = config_keys();
  std::size_t next = 0;
  for (const Row& row : rows) {
    std::string defaults;  // a row of several keys lists their defaults in order, ", " between
    for (const std::string& key : row.keys) {
      ASSERT_LT(next, schema.size()) << key << " is documented but not in the schema";
      EXPECT_EQ(key, schema[next].key) << "docs/scenes.md's keys differ from the schema's (order)";
      defaults += (defaults.empty() ? "" : ", ") + schema[next].default_value;
      ++next;
    }
    EXPECT_EQ(row.default_value, defaults) << "docs/scenes.md default of " << row.keys.front();
  }
  for (; next < schema.size(); ++next) ADD_FAILURE() << schema[next].key << " is not documented";
}

// libFuzzer reaches a key's reader only by spelling the key; its dictionary gives it the words.
TEST(ConfigSchema, TheFuzzersDictionaryNamesEveryTableAndKey) {
  const std::string dictionary =
      read_text(std::string(TOONWATER_SOURCE_DIR) + "/tests/fuzz/config.dict");
  const auto listed = [&](const std::string& word) {
    return dictionary.find("\n\"" + word + "\"\n") != std::string::npos ||
           dictionary.rfind("\"" + word + "\"\n", 0) == 0;
  };
  for (const ConfigKey& k : config_keys()) {
    const std::size_t dot = k.key.find('.');
    const std::string table = k.key.substr(0, dot), name = k.key.substr(dot + 1);
    EXPECT_TRUE(listed(table == "object" ? "[[object]]" : "[" + table + "]"))
        << "tests/fuzz/config.dict lacks the table of " << k.key;
    EXPECT_TRUE(listed(name)) << "tests/fuzz/config.dict lacks " << k.key;
  }
}

TEST(ConfigSchema, EveryKeyHasATypeAndHelp) {
  const std::vector<ConfigKey> schema = config_keys();
  EXPECT_EQ(schema.size(), 69u);
  for (const ConfigKey& k : schema) {
    EXPECT_FALSE(k.type.empty()) << k.key;
    EXPECT_FALSE(k.help.empty()) << k.key;
    EXPECT_FALSE(k.default_value.empty()) << k.key;
  }
}

TEST(ConfigSchema, DefaultsShownAreTheStructsDefaults) {
  const auto find = [](const std::string& key) {
    for (const ConfigKey& k : config_keys())
      if (k.key == key) return k;
    return ConfigKey{};
  };
  EXPECT_EQ(find("camera.angle").default_value, "40");
  EXPECT_EQ(find("water.dt_medium").default_value, "-0.05");
  EXPECT_EQ(find("water.shading").default_value, "\"toon\"");
  EXPECT_EQ(find("light.color").default_value, "[1,1,1]");
  EXPECT_EQ(find("render.width").default_value, "640");
  EXPECT_EQ(find("render.width").type, "whole number from 1 to 16384");
  EXPECT_EQ(find("render.fps").default_value, "24");
  EXPECT_EQ(find("render.fps").type, "whole number from 1 to 240");
  EXPECT_EQ(find("flow.style").type, "\"regions\" | \"lines\" | \"regions+lines\"");
  EXPECT_EQ(find("outline.enabled").default_value, "true");
}

// The error for `toml` from "scene.toml" on: the scratch directory before it varies.
std::string error_in_file(const std::string& toml) {
  const std::string error = config_error(toml);
  const std::size_t file = error.find("scene.toml:");
  return file == std::string::npos ? error : error.substr(file);
}

TEST(ConfigSchema, IntegerKeysTakeWholeNumbersOnly) {
  EXPECT_EQ(config_from("[render]\nwidth = 320\nheight = 200.0\n").render.height, 200);
  EXPECT_EQ(config_from("[flow]\nsmoothing = 7\n").flow.analysis.flow_smoothing, 7);
  EXPECT_EQ(error_in_file("[render]\nquality = \"draft\"\nwidth = 2.5\n"),
            "scene.toml:3: config: 'render.width' must be a whole number");
  EXPECT_EQ(error_in_file("# counts\n[flow]\nsmoothing = 2.5\n"),
            "scene.toml:3: config: 'flow.smoothing' must be a whole number");
  EXPECT_EQ(error_in_file("[render]\nheight = \"tall\"\n"),
            "scene.toml:2: config: 'render.height' must be a whole number");
  EXPECT_EQ(config_from("[render]\nfps = 30\n").render.fps, 30);
  EXPECT_EQ(error_in_file("[render]\nfps = 29.97\n"),
            "scene.toml:2: config: 'render.fps' must be a whole number");
  EXPECT_EQ(error_in_file("[render]\nfps = 0\n"),
            "scene.toml:2: config: 'render.fps' must be between 1 and 240");
  // Compared as integers: no rounding of a 64-bit value through a double into range.
  EXPECT_EQ(error_in_file("[render]\nwidth = 9223372036854775807\n"),
            "scene.toml:2: config: 'render.width' must be between 1 and 16384");
  EXPECT_EQ(error_in_file("[render]\nwidth = 1e300\n"),
            "scene.toml:2: config: 'render.width' must be between 1 and 16384");
  // From --set: no file, so the key alone.
  EXPECT_EQ(config_error("", {"render.width=2.5"}),
            "config: 'render.width' must be a whole number");
}

TEST(ConfigSchema, ValueErrorsInAFileNameItsLine) {
  EXPECT_EQ(error_in_file("[water]\n\nior = 9\n"),
            "scene.toml:3: config: 'water.ior' must be between 1 and 3");
  EXPECT_EQ(error_in_file("[camera]\nangle = 40\n[outline]\ncolour = [0, 0, 0]\n"),
            "scene.toml:4: config: 'outline.colour' is not a known key");
  EXPECT_EQ(error_in_file("[render]\nframes = \"9-2\"\n"),
            "scene.toml:2: config: 'render.frames' must be a frame range A-B with A <= B");
}

TEST(ConfigSchema, ErrorsBetweenKeysOrOfAMissingKeyNameTheirTablesLine) {
  EXPECT_EQ(error_in_file("\n[camera]\nlocation = [1, 2, 3]\nlook_at = [1, 2, 3]\n"),
            "scene.toml:2: config: 'camera.look_at' must differ from camera.location");
  EXPECT_EQ(error_in_file("[light]\ndirection = [1, 1, 1]\nposition = [0, 5, 0]\n"),
            "scene.toml:1: config: 'light.position' excludes light.direction: give one");
  EXPECT_EQ(error_in_file("[water]\nior = 1.33\n\n[[object]]\nname = \"s\"\n"),
            "scene.toml:4: config: 'object.0.mesh' is required (a mesh file or sequence pattern)");
  EXPECT_EQ(error_in_file("\nobject = 5\n"),
            "scene.toml:2: config: 'object' must be an array of tables: [[object]]");
}

}  // namespace
}  // namespace toonwater::test
