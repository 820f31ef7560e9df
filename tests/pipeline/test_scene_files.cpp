// povgen without rendering: configuration errors, the mesh2 text, which constructs minimal and
// full scenes contain, and that hostile names never reach the scene raw.
#include "scene/config.hpp"
#include "scene/mesh2_writer.hpp"
#include "scene/scene_mesh.hpp"
#include "tests/support/povray_test_util.hpp"
#include "tests/support/scene_config.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>

#include <regex>

namespace toonwater::test {
namespace {

TEST(PovgenConfig, DefaultsAreThePapersChoices) {
  const auto c = config_from("");
  EXPECT_GT(c.water.t_bright, c.water.t_medium);
  EXPECT_DOUBLE_EQ(c.water.ior, 1.33);
  EXPECT_TRUE(c.outline.enabled);
  EXPECT_TRUE(c.flow.enabled);
  EXPECT_TRUE(c.objects.empty());
}

TEST(PovgenConfig, ReadsEveryKindOfValueAndOverrides) {
  const auto c = config_from(
      "[water]\nior = 1.2\nbright = [1, 0.5, 0]\n[light]\nposition = [1, 2, 3]\n"
      "[[object]]\nmesh = \"ball.obj\"\nreflection = \"abstract\"\n",
      {"water.ior=1.5", "object.0.color=[0, 1, 0]", "render.frames=3-7", "outline.units=world"});
  EXPECT_DOUBLE_EQ(c.water.ior, 1.5);
  EXPECT_DOUBLE_EQ(c.water.bright[1], 0.5);
  ASSERT_TRUE(c.light.position.has_value());
  EXPECT_DOUBLE_EQ(c.light.position->z(), 3.0);
  ASSERT_EQ(c.objects.size(), 1u);
  EXPECT_EQ(c.objects[0].name, "ball");
  EXPECT_EQ(c.objects[0].reflection, ReflectionTarget::abstract);
  EXPECT_DOUBLE_EQ(c.objects[0].color[1], 1.0);
  ASSERT_TRUE(c.render.frames.has_value());
  EXPECT_EQ(c.render.frames->first, 3);
  EXPECT_EQ(c.render.frames->last, 7);
  EXPECT_EQ(c.outline.units, WidthUnits::world);
}

TEST(PovgenConfig, BandThresholdsAreRelativeUnlessAbsoluteOnesAreGiven) {
  EXPECT_EQ(config_from("").water.bands, BandThresholds::relative);
  EXPECT_EQ(config_from("[water]\nt_bright = 0.6\n").water.bands, BandThresholds::absolute);
  EXPECT_EQ(config_from("[water]\nt_medium = 0.1\nbands = \"relative\"\n").water.bands,
            BandThresholds::relative);
  const auto c = config_from("", {"water.dt_bright=0.1", "water.dt_medium=-0.2"});
  EXPECT_DOUBLE_EQ(c.water.dt_bright, 0.1);
  EXPECT_DOUBLE_EQ(c.water.dt_medium, -0.2);
  EXPECT_NE(config_error("", {"water.dt_medium=0.1"}).find("'water.dt_medium'"), std::string::npos);
  EXPECT_NE(config_error("", {"water.bands=steep"}).find("'water.bands'"), std::string::npos);
  EXPECT_NE(config_error("", {"water.body=glass"}).find("'water.body'"), std::string::npos);
  // Outline widths are in pixels by default; a unit's own default width applies when none is given.
  EXPECT_EQ(c.outline.units, WidthUnits::pixels);
  EXPECT_FALSE(c.outline.width.has_value());
  EXPECT_EQ(config_from("", {"water.body=clear"}).water.body, WaterBody::clear);
}

TEST(PovgenConfig, ErrorsNameTheKey) {
  EXPECT_NE(config_error("[water]\niorr = 1.2\n").find("'water.iorr'"), std::string::npos);
  EXPECT_NE(config_error("[water]\nior = \"high\"\n").find("'water.ior' must be a number"),
            std::string::npos);
  EXPECT_NE(config_error("[outline]\ncolor = [0, 0]\n").find("'outline.color'"), std::string::npos);
  EXPECT_NE(config_error("[flow]\nridge_color = [2, 0, 0]\n").find("'flow.ridge_color'"),
            std::string::npos);
  EXPECT_NE(
      config_error("[outline]\nenabled = 1\n").find("'outline.enabled' must be true or false"),
      std::string::npos);
  EXPECT_NE(config_error("[[object]]\nmesh = \"a.obj\"\nreflection = \"mirror\"\n")
                .find("'object.0.reflection' must be one of"),
            std::string::npos);
  EXPECT_NE(config_error("[[object]]\ncolor = [1, 0, 0]\n").find("'object.0.mesh' is required"),
            std::string::npos);
  EXPECT_NE(config_error("[sky]\ncolor = [1, 1, 1]\n").find("'sky'"), std::string::npos);
  EXPECT_NE(config_error("", {"water.kt=0.3"}).find("'water.kt'"), std::string::npos);
  EXPECT_NE(config_error("", {"render.frames=9-2"}).find("'render.frames'"), std::string::npos);
  EXPECT_NE(config_error("", {"object.0.color=[1,0,0]"}).find("'object.0.color'"),
            std::string::npos);
  EXPECT_NE(config_error("[water\n").find("scene.toml:1"), std::string::npos);
}

TEST(PovgenConfig, IdentifiersAreSanitisedAndUnique) {
  EXPECT_EQ(sanitize_identifier("a\"}#declare\nX"), "a___declare_X");
  EXPECT_EQ(sanitize_identifier(""), "object");
  const auto c = config_from(
      "[[object]]\nmesh = \"x.obj\"\nname = \"boat\"\n[[object]]\nmesh = \"y.obj\"\nname = "
      "\"boat\"\n");
  EXPECT_EQ(c.objects[0].name, "boat");
  EXPECT_EQ(c.objects[1].name, "boat_2");
}

// ---- mesh2 ----

TEST(PovgenMesh2, LeavesOutDegenerateFacesReplacesZeroNormalsNeverWritesNan) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {2, 0, 0}, {5, 5, 5}, {1.23456789, 0, 0}};
  m.triangles = {
      {0, 2, 1}, {0, 1, 3}, {1, 1, 2}};  // a good face, a collinear one, a repeated corner
  std::vector<Vec3> normals(m.positions.size(), Vec3::Zero());  // all undefined
  const SceneMesh sm = make_scene_mesh(m, normals, false, Axis::y);
  EXPECT_EQ(sm.triangles.size(), 1u);
  EXPECT_EQ(sm.degenerate_faces, 2u);
  EXPECT_EQ(sm.replaced_normals, m.positions.size());
  for (const Vec3& n : sm.normals) EXPECT_NEAR(n.norm(), 1.0, 1e-12);
  EXPECT_NEAR(sm.normals[0].y(), 1.0, 1e-12);  // from the face (0,2,1): up
  EXPECT_NEAR(sm.normals[4].y(), 1.0, 1e-12);  // isolated: the up axis

  std::string text;
  const auto uv = toon_coordinates(sm, {}, {});
  append_mesh2(text, "M", sm, uv);
  EXPECT_NE(text.find("vertex_vectors { 6,"), std::string::npos);
  EXPECT_NE(text.find("normal_vectors { 6,"), std::string::npos);
  EXPECT_NE(text.find("uv_vectors { 6,"), std::string::npos);
  EXPECT_NE(text.find("face_indices { 1,"), std::string::npos);
  EXPECT_NE(text.find("<1.234568,0,0>"), std::string::npos) << "7 significant digits";
  EXPECT_EQ(text.find("inside_vector"), std::string::npos) << "open mesh";
  EXPECT_EQ(text.find("nan"), std::string::npos);
  EXPECT_EQ(text.find("inf"), std::string::npos);
}

TEST(PovgenMesh2, ClosedMeshesGetAnInsideVectorAndShellsMoveAlongNormals) {
  const TriangleMesh sphere = make_sphere(Vec3::Zero(), 1.0, 6, 8);
  std::vector<Vec3> normals;
  for (const Vec3& p : sphere.positions) normals.push_back(p.normalized());
  const SceneMesh sm = make_scene_mesh(sphere, normals, true, Axis::y);
  std::string text;
  append_shell_mesh2(text, "S", sm, std::vector<double>(sm.positions.size(), 0.5));
  EXPECT_NE(text.find("inside_vector"), std::string::npos);
  EXPECT_EQ(text.find("uv_vectors"), std::string::npos);
  EXPECT_NE(text.find("<0,1.5,0>"), std::string::npos) << text.substr(0, 200);
}

TEST(PovgenMesh2, BandCoordinateFollowsLightDotNormalForParallelAndPointLights) {
  TriangleMesh m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 0, 1}};
  m.triangles = {{0, 2, 1}};
  const std::vector<Vec3> up(3, Vec3(0, 1, 0));
  const SceneMesh sm = make_scene_mesh(m, up, false, Axis::y);
  LightGeometry sun;
  sun.vector = Vec3(0, 1, 0);
  const std::vector<double> flow_field{-1.0, 0.25, 9.0};  // 9 is clamped at 4
  auto uv = toon_coordinates(sm, sun, flow_field);
  EXPECT_NEAR(uv[0][0], 0.5 + 0.4999, 1e-6);
  EXPECT_NEAR(uv[0][1], 0.5 - 0.12, 1e-6);
  EXPECT_NEAR(uv[1][1], 0.5 + 0.03, 1e-6);
  EXPECT_NEAR(uv[2][1], 0.5 + 0.48, 1e-6);
  LightGeometry lamp{false, Vec3(1, 1, 0)};  // 45° above vertex 0, straight above vertex 1
  uv = toon_coordinates(sm, lamp, {});
  EXPECT_NEAR(uv[0][0], 0.5 + 0.4999 * std::sqrt(0.5), 1e-6);
  EXPECT_NEAR(uv[1][0], 0.5 + 0.4999, 1e-6);
  EXPECT_NEAR(uv[0][1], 0.5, 1e-6);
}

// ---- scene constructs ----

struct Generated {
  std::string pov, water_inc, ini;
  CommandResult result;
};

Generated generate(const ScratchDir& dir, std::vector<std::string> args) {
  std::vector<std::string> full{"povgen", "--out", (dir / "scene").string()};
  full.insert(full.end(), args.begin(), args.end());
  Generated g;
  g.result = run_toonwater(full);
  if (g.result.exit_code != 0) return g;
  g.pov = read_text(dir / "scene" / "scene.pov");
  g.ini = read_text(dir / "scene" / "scene.ini");
  g.water_inc = read_text(dir / "scene" / "water_0000.inc");
  return g;
}

TEST(PovgenScene, MinimalSceneContainsOnlyWhatItNeeds) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(9, 1.0, [](double, double) { return 0.0; }));
  const Generated g =
      generate(dir, {"--water", (dir / "water.obj").string(), "--set", "flow.enabled=false",
                     "--set", "outline.enabled=false", "--set", "water.ks=0", "--set",
                     "water.reflection=0", "--set", "water.transmit=0"});
  ASSERT_EQ(g.result.exit_code, 0) << g.result.output;
  for (const char* absent :
       {"light_source", "reflection", "interior", "Toon_outline_shell", "Toon_bands_with_flow",
        "Obj_", "no_reflection", "phong", "Toon_silhouette", "#include \"obj_", "max_trace_level"})
    EXPECT_EQ(g.pov.find(absent), std::string::npos) << absent;
  for (const char* present :
       {"#include \"toon.inc\"", "Toon_bands(", "Water_mesh", "camera", "background"})
    EXPECT_NE(g.pov.find(present), std::string::npos) << present;
  EXPECT_EQ(g.water_inc.find("Water_shell"), std::string::npos);
  EXPECT_EQ(g.water_inc.find("inside_vector"), std::string::npos);
  EXPECT_EQ(g.ini.find("Initial_Frame"), std::string::npos);
  // The scene's toon.inc holds only the macros it calls: not a word of what it does not use.
  const std::string toon = read_text(dir / "scene" / "toon.inc");
  EXPECT_NE(toon.find("#macro Toon_bands("), std::string::npos);
  std::string everything = g.pov + toon;
  std::transform(everything.begin(), everything.end(), everything.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* absent :
       {"interior_texture", "no_image", "no_reflection", "ior", "reflection", "toon_outline_shell",
        "toon_bands_with_flow", "toon_object_bands", "toon_silhouette", "clipped_by", "sky"})
    EXPECT_EQ(everything.find(absent), std::string::npos) << absent;
  EXPECT_FALSE(std::filesystem::exists(dir / "scene" / "obj_water.inc"));
}

TEST(PovgenScene, FullSceneHasEveryFeature) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_sphere(Vec3::Zero(), 1.0, 8, 12));
  write_obj(dir / "ball.obj", make_sphere(Vec3(0, -0.2, 0), 0.3, 6, 8));
  write_obj(dir / "kite.obj", make_sphere(Vec3(0, 3, 0), 0.3, 6, 8));
  write_text(dir / "scene.toml",
             "[[object]]\nmesh = \"ball.obj\"\nreflection = \"none\"\n"
             "[[object]]\nmesh = \"kite.obj\"\nreflection = \"abstract\"\noutline = false\n");
  const Generated g = generate(
      dir, {"--water", (dir / "water.obj").string(), "--config", (dir / "scene.toml").string()});
  ASSERT_EQ(g.result.exit_code, 0) << g.result.output;
  for (const char* present :
       {"light_source", "parallel", "reflection { 0.2 }", "interior { ior 1.33 }",
        "Toon_outline_shell(Water_shell", "Toon_flow_over(Toon_bands(", "#include \"obj_ball.inc\"",
        "Obj_ball_mesh", "Toon_outline_shell(Obj_ball_shell", "no_reflection",
        "Toon_silhouette(Obj_kite_mesh", "phong 0.5", "max_trace_level 10"})
    EXPECT_NE(g.pov.find(present), std::string::npos) << present;
  // The ball crosses the water line: its shell is split there, the part under it with the
  // water's ior and a line colour seen through the surface (negative: it takes away the
  // surface's own colour); its texture changes in the water, with a contact line. The kite
  // (above) has no shell at all.
  EXPECT_NE(g.pov.find("Toon_outline_shell(Obj_ball_shell, rgb <-"), std::string::npos);
  EXPECT_NE(g.pov.find(") clipped_by { plane { y, Obj_ball_water_line } } interior { ior 1.33 }"),
            std::string::npos);
  EXPECT_NE(g.pov.find("Toon_outline_shell(Obj_ball_shell, srgb <0, 0, 0>) clipped_by { plane "
                       "{ -y, -Obj_ball_water_line } } no_reflection }"),
            std::string::npos);
  EXPECT_NE(g.pov.find("Toon_in_water(Obj_ball_water, Obj_ball_contact,"), std::string::npos);
  EXPECT_EQ(g.pov.find("Toon_in_water(Obj_kite"), std::string::npos);
  EXPECT_NE(g.water_inc.find("#declare Obj_ball_water_line = "), std::string::npos);
  EXPECT_NE(
      g.water_inc.find("#declare Obj_ball_water = intersection { object { Water_mesh } box {"),
      std::string::npos);
  EXPECT_NE(g.water_inc.find("#declare Obj_ball_contact = "), std::string::npos);
  // A see-through closed volume: free surface and body have their own textures, and each its
  // two bands where dark meets bright; the free surface's is the object's, given by no index.
  for (const char* texture : {"Water_surface_texture = texture {\n  Toon_flow_over(Toon_bands(",
                              "Water_surface_two_band_texture = texture {\n  "
                              "Toon_flow_over(Toon_two_bands(",
                              "Water_body_texture = texture {\n  Toon_bands(",
                              "Water_body_two_band_texture = texture {\n  Toon_two_bands(",
                              "Water_only_dark_texture = texture {\n  Toon_flow_over(pigment {",
                              "Water_only_bright_texture = texture {\n  Toon_flow_over(pigment {"})
    EXPECT_NE(g.pov.find(std::string("#declare ") + texture), std::string::npos) << texture;
  EXPECT_NE(g.pov.find("Water_mesh\n  texture {\n    Water_surface_texture\n"), std::string::npos);
  EXPECT_NE(g.water_inc.find("texture_list { 6, texture { Water_surface_two_band_texture }, "
                             "texture { Water_body_texture }, texture { "
                             "Water_body_two_band_texture }, texture { Water_only_dark_texture }, "
                             "texture { Water_only_medium_texture }, texture { "
                             "Water_only_bright_texture } }"),
            std::string::npos);
  // Reflected rays that miss everything see a flat sky, which the camera does not see.
  EXPECT_NE(g.pov.find("hollow no_image no_shadow"), std::string::npos);
  const std::string toon = read_text(dir / "scene" / "toon.inc");
  for (const char* macro : {"Toon_bands(", "Toon_two_bands(", "Toon_flow_over(",
                            "Toon_object_bands(", "Toon_outline_shell(", "Toon_silhouette("})
    EXPECT_NE(toon.find(std::string("#macro ") + macro), std::string::npos) << macro;
  EXPECT_EQ(g.pov.find("Obj_kite_shell"), std::string::npos);
  EXPECT_NE(g.water_inc.find("Water_shell"), std::string::npos);
  EXPECT_NE(g.water_inc.find("inside_vector"), std::string::npos);
  EXPECT_NE(read_text(dir / "scene" / "obj_kite.inc").find("inside_vector"), std::string::npos);
  EXPECT_EQ(read_text(dir / "scene" / "obj_kite.inc").find("Obj_kite_shell"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "scene" / "toon.inc"));
}

TEST(PovgenScene, HostileNamesAndValuesNeverReachTheSceneRaw) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(5, 1.0, [](double, double) { return 0.0; }));
  write_obj(dir / "a.obj", make_sphere(Vec3(0, 0.5, 0), 0.2, 6, 8));
  write_text(dir / "scene.toml",
             "[[object]]\nmesh = \"a.obj\"\nname = \"x\\\"}\\n#fopen F \\\"/etc/passwd\\\" "
             "read\"\n");
  const Generated g = generate(
      dir, {"--water", (dir / "water.obj").string(), "--config", (dir / "scene.toml").string()});
  ASSERT_EQ(g.result.exit_code, 0) << g.result.output;
  EXPECT_EQ(g.pov.find("#fopen"), std::string::npos);
  EXPECT_EQ(g.pov.find("passwd\""), std::string::npos);
  EXPECT_NE(g.pov.find("Obj_x____fopen_F"), std::string::npos) << g.pov;
  // A value that is not a number never gets in either.
  const Generated bad = generate(
      dir, {"--water", (dir / "water.obj").string(), "--set", "water.ior=1.33 } #declare X = 1"});
  EXPECT_NE(bad.result.exit_code, 0);
  EXPECT_NE(bad.result.output.find("'water.ior' must be a number"), std::string::npos)
      << bad.result.output;
}

TEST(PovgenScene, GlobSequencesStaticAndAnimatedObjectsMatchedByFrame) {
  ScratchDir dir;
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 3 2\n";
  for (int f : {7, 8, 9}) {
    write_text(dir / ("wave" + std::to_string(f) + ".obj"), tri);
    write_text(dir / ("boat_" + std::to_string(f) + ".obj"), tri);
  }
  write_text(dir / "rock.obj", tri);
  const std::filesystem::path out = dir / "scene";
  CommandResult r =
      run_toonwater({"povgen", "--water", (dir / "wave*.obj").string(), "--object",
                     (dir / "boat_*.obj").string(), "--object", (dir / "rock.obj").string(),
                     "--set", "render.frames=8-9", "--out", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(std::filesystem::exists(out / "water_0007.inc"));
  for (const char* f : {"water_0008.inc", "water_0009.inc", "obj_boat.0008.inc",
                        "obj_boat.0009.inc", "obj_rock.inc"})
    EXPECT_TRUE(std::filesystem::exists(out / f)) << f;
  const std::string ini = read_text(out / "scene.ini");
  EXPECT_NE(ini.find("Initial_Frame=8\nFinal_Frame=9"), std::string::npos) << ini;
  EXPECT_NE(ini.find("\n; Frame_Rate=24\n"), std::string::npos) << ini;  // render.fps's default
  const std::string pov = read_text(out / "scene.pov");
  EXPECT_NE(pov.find("#include concat(\"obj_boat.\", str(frame_number, -4, 0), \".inc\")"),
            std::string::npos);
  EXPECT_NE(pov.find("#include \"obj_rock.inc\""), std::string::npos);

  // An animated object must exist for every water frame.
  std::filesystem::remove(dir / "boat_9.obj");
  r = run_toonwater({"povgen", "--water", (dir / "wave*.obj").string(), "--object",
                     (dir / "boat_*.obj").string(), "--out", (dir / "scene2").string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("no file for frame 9"), std::string::npos) << r.output;
}

TEST(PovgenScene, BadInputGetsAClearErrorAndNoScene) {
  ScratchDir dir;
  CommandResult r = run_toonwater({"povgen", "--water", (dir / "missing_####.obj").string(),
                                   "--out", (dir / "scene").string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("missing_####.obj"), std::string::npos) << r.output;
  write_text(dir / "water_0001.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
  write_text(dir / "water_0003.obj", "v 0 0 0\nv 1 0 0\nv 0 0 1\nf 1 2 3\n");
  r = run_toonwater(
      {"povgen", "--water", (dir / "water_####.obj").string(), "--out", (dir / "scene").string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("frame 2 is missing"), std::string::npos) << r.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "scene" / "scene.pov"));
}

// --scale/--translate (or --transform) map the water from file to world coordinates, as for
// Mantaflow caches; a singular map is refused before anything is read or written.
TEST(PovgenScene, WaterTransformMapsFileToWorldCoordinates) {
  ScratchDir dir;
  write_text(dir / "w.obj", "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nf 1 2 3 4\n");
  const CommandResult r =
      run_toonwater({"povgen", "--water", (dir / "w.obj").string(), "--scale", "2", "--translate",
                     "10,0,0", "--set", "flow.enabled=false", "--out", (dir / "s").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // y up: (x, y, z) -> POV-Ray (x, y, -z).
  EXPECT_NE(
      read_text(dir / "s" / "water_0000.inc").find("<10,0,0>, <12,0,0>, <12,0,-2>, <10,0,-2>"),
      std::string::npos);
  const CommandResult singular = run_toonwater({"povgen", "--water", (dir / "w.obj").string(),
                                                "--scale", "0", "--out", (dir / "bad").string()});
  EXPECT_NE(singular.exit_code, 0);
  EXPECT_NE(singular.output.find("singular"), std::string::npos) << singular.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad"));
}

// [render] quality picks the size and antialiasing written to scene.ini; antialias = false
// turns antialiasing off whatever the quality.
TEST(PovgenScene, RenderQualityPresetsReachSceneIni) {
  ScratchDir dir;
  write_obj(dir / "water.obj", make_height_grid(5, 1.0, [](double, double) { return 0.0; }));
  auto ini = [&](const std::string& name, std::vector<std::string> sets) {
    std::vector<std::string> args{"--water", (dir / "water.obj").string(),
                                  "--set",   "render.width=300",
                                  "--set",   "render.height=200"};
    for (const auto& s : sets) args.insert(args.end(), {"--set", s});
    const CommandResult r = run_toonwater([&] {
      std::vector<std::string> full{"povgen"};
      full.insert(full.end(), args.begin(), args.end());
      full.insert(full.end(), {"--out", (dir / name).string()});
      return full;
    }());
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return read_text(dir / name / "scene.ini");
  };
  const std::string draft = ini("draft", {"render.quality=draft"});
  EXPECT_NE(draft.find("Width=150\nHeight=100\nAntialias=Off\n"), std::string::npos) << draft;
  const std::string preview = ini("preview", {"render.quality=preview"});
  EXPECT_NE(preview.find("Width=300\nHeight=200\nAntialias=Off\n"), std::string::npos) << preview;
  const std::string final_ini = ini("final", {});  // the default
  EXPECT_NE(final_ini.find("Antialias=On\nAntialias_Threshold=0.05\nAntialias_Depth=3\n"),
            std::string::npos)
      << final_ini;
  const std::string forced_off = ini("off", {"render.quality=final", "render.antialias=false"});
  EXPECT_NE(forced_off.find("Antialias=Off"), std::string::npos) << forced_off;

  const CommandResult bad =
      run_toonwater({"povgen", "--water", (dir / "water.obj").string(), "--set",
                     "render.quality=ultra", "--out", (dir / "bad").string()});
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.output.find("render.quality"), std::string::npos) << bad.output;
}

// A frame with no liquid (an empty mesh) is reported and left without water; the sequence goes
// on and still renders with one povray command. With --maps the empty frame gets no map.
TEST(PovgenScene, EmptyFrameIsReportedAndTheSequenceGoesOn) {
  ScratchDir dir;
  write_obj(dir / "water_0001.obj", make_height_grid(5, 1.0, [](double, double) { return 0.0; }));
  write_text(dir / "water_0002.obj", "# the liquid has left the domain\n");
  write_obj(dir / "water_0003.obj", make_height_grid(5, 1.0, [](double, double) { return 0.0; }));
  const std::filesystem::path out = dir / "scene", maps = dir / "maps";
  const CommandResult r = run_toonwater({"povgen", "--water", (dir / "water_####.obj").string(),
                                         "--set", "render.width=16", "--set", "render.height=12",
                                         "--out", out.string(), "--maps", maps.string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("water_0002.obj: contains no faces; that frame shows no water"),
            std::string::npos)
      << r.output;
  EXPECT_NE(read_text(out / "water_0002.inc").find("#declare Water_mesh = union {}"),
            std::string::npos);
  const Povray p = run_povray(out);
  EXPECT_EQ(p.exit_code, 0) << p.output;
  for (const char* frame : {"frame_1.png", "frame_2.png", "frame_3.png"})
    EXPECT_TRUE(std::filesystem::exists(out / frame)) << frame;
  EXPECT_TRUE(std::filesystem::exists(maps / "water_0001.exr"));
  EXPECT_FALSE(std::filesystem::exists(maps / "water_0002.exr"));

  // A single empty file is still an error: there is nothing to render.
  const CommandResult single = run_toonwater(
      {"povgen", "--water", (dir / "water_0002.obj").string(), "--out", (dir / "one").string()});
  EXPECT_NE(single.exit_code, 0);
  EXPECT_NE(single.output.find("contains no faces"), std::string::npos) << single.output;
}

}  // namespace
}  // namespace toonwater::test
