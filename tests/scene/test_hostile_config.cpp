// Huge and hostile scene configurations: deep nesting, enormous files and overrides, stray
// non-ASCII bytes get a clear ConfigError (or are read correctly), never a crash. Two are
// regression tests for what fuzzing found in toml++ 3.3 (scene/toml_guard.hpp:
// check_before_parsing): a stack overflow on deep dotted keys, and undefined behaviour
// (__builtin_unreachable) on non-ASCII characters outside strings.
#include "scene/config.hpp"
#include "tests/support/scene_config.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace toonwater::test {
namespace {

std::string repeat(const std::string& piece, int times) {
  std::string out;
  out.reserve(piece.size() * static_cast<std::size_t>(times));
  for (int i = 0; i < times; ++i) out += piece;
  return out;
}

constexpr int deep = 200000;

TEST(HostileConfig, DeepDottedKeysAreRejectedBeforeParsing) {
  for (const std::string& toml :
       {"a" + repeat(".a", deep) + " = 1\n", "[" + repeat("a.", deep) + "a]\n",
        "[[" + repeat("a.", deep) + "a]]\n", "[water]\n" + repeat("\"q\" . ", deep) + "x = 1\n"}) {
    const std::string error = config_error(toml);
    EXPECT_NE(error.find("scene.toml:"), std::string::npos) << error;
    EXPECT_NE(error.find(": keys nest more than 16 levels deep"), std::string::npos) << error;
  }
}

TEST(HostileConfig, DotsInStringsCommentsAndNumbersAreNotNesting) {
  const std::string dots = repeat(".x", 40);
  EXPECT_EQ(config_error("[water] # " + dots +
                         "\nior = 1.25\nbright = [0.5, 0.25, 0.125]\n"
                         "[[object]]\nmesh = \"a" +
                         dots + ".obj\"\nname = '''b" + dots + "'''\n"),
            "accepted");
}

TEST(HostileConfig, DeepOverridesAreRejected) {
  std::string error = config_error("", {repeat("a.", deep) + "a=1"});
  EXPECT_NE(error.find("is not a known key"), std::string::npos) << error.substr(0, 200);
  // Values nested too deep (dotted keys, or arrays and inline tables beyond toml++'s limit of
  // 256) are not taken as TOML: the override is then a bare string, which the key rejects.
  for (const std::string& value :
       {"{" + repeat("a.", deep) + "a = 1}", repeat("[", deep) + repeat("]", deep)}) {
    error = config_error("", {"water.ior=" + value});
    EXPECT_NE(error.find("'water.ior' must be a number"), std::string::npos)
        << error.substr(0, 200);
  }
}

TEST(HostileConfig, DeeplyNestedValuesGetAParseErrorWithTheLine) {
  for (const std::string& value :
       {repeat("[", deep) + repeat("]", deep), repeat("{a=", deep) + "1" + repeat("}", deep)}) {
    const std::string error = config_error("[water]\n\nior = " + value + "\n");
    EXPECT_NE(error.find("scene.toml:3:"), std::string::npos) << error.substr(0, 200);
    EXPECT_NE(error.find("nested"), std::string::npos) << error.substr(0, 200);
  }
}

TEST(HostileConfig, EnormousFilesAreReadOrRejectedNamingTheKey) {
  // 100k unknown keys: the first one is named.
  std::string toml = "[water]\nior = 1.2\n";
  for (int i = 0; i < 100000; ++i) {
    const std::string number = std::to_string(i);
    toml.append("k").append(number).append(" = ").append(number).append("\n");
  }
  std::string error = config_error(toml);
  EXPECT_NE(error.find("'water.k0' is not a known key"), std::string::npos) << error;

  // A megabyte string where a number belongs.
  error = config_error("[water]\nior = \"" + std::string(1 << 20, 'x') + "\"\n");
  EXPECT_NE(error.find("'water.ior' must be a number"), std::string::npos) << error.substr(0, 200);

  // 20k objects of one name: all read, names made unique (in n log n: no quadratic search).
  ScratchDir dir;
  write_text(dir / "scene.toml",
             repeat("[[object]]\nmesh = \"ball.obj\"\nname = \"boat\"\n", 20000));
  ConfigSources sources;
  sources.file = dir / "scene.toml";
  const SceneConfig config = load_config(sources);
  ASSERT_EQ(config.objects.size(), 20000u);
  EXPECT_EQ(config.objects[0].name, "boat");
  EXPECT_EQ(config.objects[1].name, "boat_2");
  EXPECT_EQ(config.objects[19999].name, "boat_20000");
}

TEST(HostileConfig, NonAsciiOutsideStringsIsRejectedBeforeParsing) {
  // The fuzzer's input, reduced: U+048E in a table header.
  std::string error = config_error("[water]\nior = 1.2\n[[objec\xd2\x8e]]\nmesh = \"a.obj\"\n");
  EXPECT_NE(error.find("scene.toml:3: non-ASCII character outside a string or comment"),
            std::string::npos)
      << error;
  error = config_error("[water]\nior = 1.2\xc3\xa9\n");  // 1.2é
  EXPECT_NE(error.find("scene.toml:2: non-ASCII"), std::string::npos) << error;
  // marzer/tomlplusplus issue 190: a line-ending backslash in a multi-line basic string.
  error = config_error("[[object]]\nmesh = \"a.obj\"\nname = \"\"\"\\\n\xc2\xa7\"\"\"\n");
  EXPECT_NE(error.find("scene.toml:4: non-ASCII text in a \"\"\" string"), std::string::npos)
      << error;
  // The fuzzer's second input, reduced: a quote that opens no string, then U+027E.
  error = config_error("", {"render.frames=3-7'7\xc9\xbe"});
  EXPECT_NE(error.find("'render.frames' must be a frame range"), std::string::npos) << error;
  error = config_error("[render]\nframes = 3-7'7\xc9\xbe\n");
  EXPECT_NE(error.find("scene.toml:2: non-ASCII character outside a string"), std::string::npos)
      << error;
}

TEST(HostileConfig, NonAsciiInStringsCommentsAndBareOverridesIsRead) {
  ScratchDir dir;
  write_text(dir / "scene.toml",
             "# caf\xc3\xa9 \xe2\x98\x83\n[[object]]\nmesh = \"\xe6\xb0\xb4.obj\"\n"
             "name = '\xe6\xb0\xb4\xe9\x9d\xa2'\n[[object]]\nmesh = '''b\xc3\xa9.obj'''\n");
  ConfigSources sources;
  sources.file = dir / "scene.toml";
  sources.overrides = {"object.1.name=caf\xc3\xa9"};  // a bare word: a string
  const SceneConfig config = load_config(sources);
  ASSERT_EQ(config.objects.size(), 2u);
  EXPECT_EQ(config.objects[0].mesh, "\xe6\xb0\xb4.obj");
  EXPECT_EQ(config.objects[0].name, "______");
  EXPECT_EQ(config.objects[1].mesh, "b\xc3\xa9.obj");
  EXPECT_EQ(config.objects[1].name, "caf__");
}

TEST(HostileConfig, AnObjectIndexTooLargeForAnIntegerNamesNoObject) {
  // 2^64 and beyond once overflowed to index 0, renaming the first object.
  const std::string objects = "[[object]]\nmesh = \"a.obj\"\n";
  for (const std::string index : {"18446744073709551616", "99999999999999999999", "1"}) {
    // Built by appending: GCC 12 misreports "literal" + string (-Wrestrict).
    std::string key = "object.";
    key += index;
    key += ".name";
    const std::string error = config_error(objects, {key + "=zzz"});
    EXPECT_NE(error.find("'" + key + "' does not name an object"), std::string::npos) << error;
  }
}

TEST(HostileConfig, BinaryGarbageAndInvalidUtf8GetAParseError) {
  std::string garbage = "[water]\nior = 1.2\n";
  garbage += "name = \"" + std::string("\xff\xfe\x00\x01\x80\xc0", 6) + "\"\n";
  std::string error = config_error(garbage);
  EXPECT_NE(error.find("scene.toml:3:"), std::string::npos) << error;
  error = config_error(std::string("\x00\x01\xff", 3));
  EXPECT_NE(error.find("scene.toml:1:"), std::string::npos) << error;
}

}  // namespace
}  // namespace toonwater::test
