// Scene-code injection: POV-Ray's language can open, read and write files (#fopen, #read,
// #write, #include), so nothing a user, a config file, a file name or a mesh supplies may reach
// scene.pov, scene.ini or an .inc file raw. Every hostile value below is either rejected with an
// error naming its key, or reduced to a validated number, keyword or identifier; and every scene
// that is written must still parse: POV-Ray renders it, and the file the payloads try to create
// never appears.
//
// The checks are structural rather than a search for the payload: every directive line of the
// scene, every string literal and every line of the .ini must be one the writer is known to emit.
// (The Water_ and Obj_ prefixes of the identifiers are the writer's own; what follows Obj_ comes
// from a name and must be [A-Za-z0-9_].)
#include "tests/support/povray_test_util.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <regex>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

// Each payload tries to make POV-Ray create `pwned.txt` in the directory it renders in, or to
// break out of a string, a block or a line.
const std::vector<std::string> payloads{
    "x\"}\n#fopen F \"pwned.txt\" write\n#write(F, \"1\")\n#fclose F\n",
    "#declare Water_mesh = sphere { 0, 1 }",
    "#include \"/etc/passwd\"",
    "a\\\"}\\n#fopen F \"pwned.txt\" write",
    "}} #end #macro M() #end { #version 3.7;",
    "\xe6\xb0\xb4\xe9\x9d\xa2 \xe2\x98\x83 caf\xc3\xa9",  // 水面 ☃ café
    "name with spaces\tand\ttabs\r\n",
};

// A TOML basic string holding `text`.
std::string toml_string(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        out += c;
    }
  }
  return out + "\"";
}

struct RunResult {
  int exit_code = -1;
  std::string output;
};

// Runs `argv` in `dir` without a shell (the directory's name may hold anything).
RunResult run_in(const fs::path& dir, const std::vector<std::string>& argv) {
  const fs::path log =
      fs::temp_directory_path() / ("toonwater-injection-" + std::to_string(::getpid()) + ".log");
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd < 0 || ::chdir(dir.c_str()) != 0) ::_exit(126);
    ::dup2(fd, STDOUT_FILENO);
    ::dup2(fd, STDERR_FILENO);
    std::vector<std::string> copies = argv;
    std::vector<char*> args;
    for (auto& a : copies) args.push_back(a.data());
    args.push_back(nullptr);
    ::execvp(args[0], args.data());
    ::_exit(127);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  RunResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  r.output = read_text(log);
  fs::remove(log);
  return r;
}

// `povray scene.ini` at 16x12 in the scene directory: the scene parses and renders.
RunResult render_tiny(const fs::path& scene) {
  return run_in(scene, {"povray", "scene.ini", "+W16", "+H12", "-A", "+WT1", "-D"});
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

bool identifier(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
  });
}

bool plain_value(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.';
  });
}

// `text` is PREFIX, then an identifier, then SUFFIX.
bool wraps_identifier(std::string_view text, std::string_view prefix, std::string_view suffix) {
  return text.size() > prefix.size() + suffix.size() && text.starts_with(prefix) &&
         text.ends_with(suffix) &&
         identifier(text.substr(prefix.size(), text.size() - prefix.size() - suffix.size()));
}

// The directives scene_writer emits.
bool known_pov_directive(std::string_view line) {
  return line == "#version 3.7;" || line == "#include \"toon.inc\"" ||
         line == "#include concat(\"water_\", str(frame_number, -4, 0), \".inc\")" ||
         wraps_identifier(line, "#include concat(\"obj_",
                          "_\", str(frame_number, -4, 0), \".inc\")") ||
         wraps_identifier(line, "#include \"obj_", ".inc\"") ||
         line == "#declare Water_surface_texture = texture {" ||
         line == "#declare Water_surface_two_band_texture = texture {" ||
         line == "#declare Water_body_texture = texture {" ||
         line == "#declare Water_body_two_band_texture = texture {" ||
         line == "#declare Water_only_dark_texture = texture {" ||
         line == "#declare Water_only_medium_texture = texture {" ||
         line == "#declare Water_only_bright_texture = texture {";
}

// The file names scene_writer quotes.
bool known_literal(std::string_view text) {
  return text == "toon.inc" || text == ".inc" || text == "water_" ||
         wraps_identifier(text, "obj_", "_") || wraps_identifier(text, "obj_", ".inc");
}

// "; comment" or "Key=value" with a plain or quoted plain value.
bool known_ini_line(std::string_view line) {
  if (line.starts_with(";")) return line.find_first_of("\"#{}") == std::string_view::npos;
  const std::size_t eq = line.find('=');
  if (eq == std::string_view::npos || !identifier(line.substr(0, eq))) return false;
  std::string_view value = line.substr(eq + 1);
  if (value.size() >= 2 && value.front() == '"' && value.back() == '"')
    value = value.substr(1, value.size() - 2);
  return plain_value(value);
}

// Every directive of scene.pov and of the per-frame .inc files is one the writer emits, every
// string literal in scene.pov names a file the writer made, every .ini line is a known key with
// a plain value; and no file holds a control character other than newline.
void expect_only_generated_code(const fs::path& scene) {
  ASSERT_TRUE(fs::exists(scene / "scene.pov"));
  for (const auto& entry : fs::directory_iterator(scene)) {
    const std::string name = entry.path().filename().string();
    const std::string text = read_text(entry.path());
    for (const char c : text)
      EXPECT_TRUE(c == '\n' || static_cast<unsigned char>(c) >= 0x20)
          << name << " has a control character";
    if (name == "toon.inc" || entry.path().extension() == ".png") continue;  // the fixed template
    for (const std::string& line : lines_of(text)) {
      const std::size_t hash = line.find('#');
      if (name == "scene.ini") {
        EXPECT_TRUE(known_ini_line(line)) << name << ": " << line;
      } else if (name == "scene.pov") {
        if (hash != std::string::npos) {
          EXPECT_TRUE(hash == 0 && known_pov_directive(line)) << name << ": " << line;
        }
        for (std::size_t open = line.find('"'); open != std::string::npos;) {
          const std::size_t close = line.find('"', open + 1);
          ASSERT_NE(close, std::string::npos) << name << ": " << line;
          EXPECT_TRUE(known_literal(std::string_view(line).substr(open + 1, close - open - 1)))
              << name << ": " << line;
          open = line.find('"', close + 1);
        }
      } else if (name == ".toonwater-scene") {
        // The marker: a fixed line, then the names of the scene's files (sanitised, and each
        // a file there); no POV-Ray code and no user text.
        const std::vector<std::string> lines = lines_of(text);
        ASSERT_FALSE(lines.empty());
        EXPECT_EQ(lines[0], "toonwater povgen scene directory");
        static const std::regex listed_name(R"(\.?[A-Za-z0-9_]+(\.[a-z]+)?|\.toonwater-scene)");
        for (std::size_t i = 1; i < lines.size(); ++i) {
          EXPECT_TRUE(std::regex_match(lines[i], listed_name)) << name << ": " << lines[i];
          EXPECT_TRUE(fs::exists(entry.path().parent_path() / lines[i])) << lines[i];
        }
      } else {
        ASSERT_EQ(entry.path().extension(), ".inc") << "unexpected file " << name;
        if (hash != std::string::npos) {
          // An object's water (object_water_declaration): numbers and fixed words only.
          static const std::string number = R"(-?[0-9.]+(e[-+]?[0-9]+)?)";
          static const std::string vector = "<" + number + ", " + number + ", " + number + ">";
          static const std::regex water_line(
              "#declare [A-Za-z0-9_]+_(water_line|contact) = " + number + ";");
          static const std::regex water("#declare [A-Za-z0-9_]+_water = (plane \\{ y, " + number +
                                        " \\}|intersection \\{ object \\{ Water_mesh \\} box \\{ " +
                                        vector + ", " + vector + " \\} \\})");
          EXPECT_TRUE(hash == 0 &&
                      (wraps_identifier(line, "#declare ", "_mesh = mesh2 {") ||
                       wraps_identifier(line, "#declare ", "_shell = mesh2 {") ||
                       std::regex_match(line, water_line) || std::regex_match(line, water)))
              << name << ": " << line;
        }
        EXPECT_EQ(line.find('"'), std::string::npos) << name << ": " << line;
      }
    }
  }
}

// Renders the scene and checks that it parsed and that no payload ran.
void expect_renders_cleanly(const fs::path& scene) {
  const RunResult r = render_tiny(scene);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(scene / "frame.png") || fs::exists(scene / "frame_0.png") ||
              fs::exists(scene / "frame_1.png"))
      << r.output;
  EXPECT_FALSE(fs::exists(scene / "pwned.txt"));
}

class Injection : public ::testing::Test {
 protected:
  void SetUp() override {
    write_obj(dir / "water.obj", make_height_grid(5, 1.0, [](double, double) { return 0.0; }));
    write_obj(dir / "ball.obj", make_sphere(Vec3(0, 0.3, 0), 0.2, 6, 8));
  }
  CommandResult povgen(std::vector<std::string> args, const fs::path& out) {
    std::vector<std::string> full{"povgen", "--water", (dir / "water.obj").string(), "--out",
                                  out.string()};
    full.insert(full.end(), args.begin(), args.end());
    return run_toonwater(full);
  }
  ScratchDir dir;
};

TEST_F(Injection, ObjectNamesFromTheConfigBecomeIdentifiers) {
  for (std::size_t i = 0; i < payloads.size(); ++i) {
    SCOPED_TRACE("payload " + std::to_string(i));
    write_text(dir / "scene.toml",
               "[[object]]\nmesh = \"ball.obj\"\nname = " + toml_string(payloads[i]) + "\n");
    const fs::path out = dir / ("config_" + std::to_string(i));
    const CommandResult r = povgen({"--config", (dir / "scene.toml").string()}, out);
    ASSERT_EQ(r.exit_code, 0) << r.output;
    expect_only_generated_code(out);
    expect_renders_cleanly(out);
  }
}

TEST_F(Injection, ObjectNamesFromSetBecomeIdentifiers) {
  for (std::size_t i = 0; i < payloads.size(); ++i) {
    SCOPED_TRACE("payload " + std::to_string(i));
    const fs::path out = dir / ("set_" + std::to_string(i));
    // Given raw (a bare word is taken as a string) and as a TOML string.
    for (const std::string& value : {payloads[i], toml_string(payloads[i])}) {
      const CommandResult r =
          povgen({"--object", (dir / "ball.obj").string(), "--set", "object.0.name=" + value}, out);
      ASSERT_EQ(r.exit_code, 0) << r.output;
      expect_only_generated_code(out);
    }
    expect_renders_cleanly(out);
  }
}

TEST_F(Injection, NonNumbersWhereNumbersBelongAreRejectedNamingTheKey) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {"water.ior", "1.33 } #fopen F \"pwned.txt\" write"},
      {"water.ior", "\"1.33\""},
      {"water.ior", "nan"},
      {"water.ks", "inf"},
      {"water.bright", "\"1, 0, 0\"}\n#declare X = 1"},
      {"water.bright", "[1, 0, \"0 } #fopen\"]"},
      {"light.color", "[1, 1, 1, 1]"},
      {"camera.angle", "\"40 #write\""},
      {"camera.location", "[0, 1, nan]"},
      {"outline.units", "\"world } #fopen\""},
      {"outline.enabled", "\"true\""},
      {"render.width", "\"64\nAntialias=On\""},
      {"render.frames", "\"1-2\n#fopen\""},
      {"object.0.reflection", "\"concrete\\\"} #write\""},
  };
  for (const auto& [key, value] : cases) {
    SCOPED_TRACE(key + "=" + value);
    const fs::path out = dir / "rejected";
    const CommandResult r =
        povgen({"--object", (dir / "ball.obj").string(), "--set", key + "=" + value}, out);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_NE(r.output.find("'" + key + "'"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out / "scene.pov"));
    // The same value in a config file is rejected the same way.
    const std::size_t dot = key.rfind('.');
    const std::string section = key.substr(0, dot), leaf = key.substr(dot + 1);
    const std::string toml =
        section == "object.0"
            ? "[[object]]\nmesh = \"ball.obj\"\n" + leaf + " = " + toml_string(value) + "\n"
            : "[" + section + "]\n" + leaf + " = " + toml_string(value) + "\n";
    write_text(dir / "scene.toml", toml);
    const CommandResult f = povgen({"--config", (dir / "scene.toml").string()}, out);
    EXPECT_NE(f.exit_code, 0);
    EXPECT_NE(f.output.find("'" + key + "'"), std::string::npos) << f.output;
    EXPECT_FALSE(fs::exists(out / "scene.pov"));
  }
}

TEST_F(Injection, HostileFileAndDirectoryNamesStayOutOfTheScene) {
  // Quotes, braces, a backslash, a newline, spaces and non-ASCII in every directory and file
  // name; '#' marks a frame number in a pattern, so it appears in the directory names only.
  const fs::path input = dir / "in \"put\" {x} \\ #fopen\n\xe6\xb0\xb4";
  fs::create_directories(input);
  const TriangleMesh water = make_height_grid(5, 1.0, [](double x, double) { return 0.1 * x; });
  for (int frame = 1; frame <= 2; ++frame)
    write_obj(input / ("w\"}{ \\n\xc3\xa9_000" + std::to_string(frame) + ".obj"), water);
  write_obj(input / "b\"all } \\ \n\xe2\x98\x83.obj", make_sphere(Vec3(0, 0.3, 0), 0.2, 6, 8));
  const fs::path out = dir / "out \"dir\" } #include \\\n\xe2\x98\x83";
  const CommandResult r = run_toonwater(
      {"povgen", "--water", (input / "w\"}{ \\n\xc3\xa9_####.obj").string(), "--object",
       (input / "b\"all } \\ \n\xe2\x98\x83.obj").string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_only_generated_code(out);
  expect_renders_cleanly(out);
  EXPECT_TRUE(fs::exists(out / "water_0001.inc"));
  EXPECT_TRUE(fs::exists(out / "water_0002.inc"));
  // `toonwater render` runs POV-Ray in that directory too.
  const CommandResult rendered = run_toonwater({"render", out.string(), "--jobs", "1"});
  EXPECT_EQ(rendered.exit_code, 0) << rendered.output;
  EXPECT_FALSE(fs::exists(out / "pwned.txt"));
}

TEST_F(Injection, MeshFileContentOtherThanNumbersNeverReachesTheScene) {
  // OBJ statements the reader skips (names, groups, materials) carry the payload.
  std::string obj =
      "o x\"}#fopen F \"pwned.txt\" write\ng #fopen F \"pwned.txt\" write\n"
      "mtllib \"x\".mtl\nusemtl }#declare\n";
  obj += "v 0 0 0\nv 1 0 0\nv 0 0 1\nv 1 0.1 1\nf 1 3 2\nf 2 3 4\n";
  write_text(dir / "named.obj", obj);
  const fs::path out = dir / "named";
  const CommandResult r =
      run_toonwater({"povgen", "--water", (dir / "named.obj").string(), "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_only_generated_code(out);
  expect_renders_cleanly(out);
}

}  // namespace
}  // namespace toonwater::test
