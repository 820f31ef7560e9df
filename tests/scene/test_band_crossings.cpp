// Faces where dark meets bright (scene/band_crossings.hpp), and how the mesh2 writer gives them
// their texture.
#include "scene/band_crossings.hpp"

#include "scene/mesh2_writer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace toonwater::test {
namespace {

constexpr double key_medium = 0.4, key_bright = 0.6;

TextureCoordinate at(double u) { return {static_cast<float>(u), 0.5F}; }

TEST(BandCrossings, AFaceIsMarkedWhenItsCornersAreDarkAndBrightAndNoneMedium) {
  // 0, 1: dark; 2, 3: bright; 4: medium.
  const std::vector<TextureCoordinate> uv{at(0.1), at(0.39), at(0.9), at(0.61), at(0.59)};
  const std::vector<Triangle> faces{
      {0, 1, 2},  // dark, dark, bright
      {0, 2, 3},  // dark, bright, bright
      {0, 2, 4},  // all three bands
      {0, 1, 4},  // dark and medium
      {2, 3, 4},  // bright and medium
      {0, 1, 1},  // dark only
      {2, 3, 3},  // bright only
  };
  const std::vector<bool> marked = dark_bright_faces(faces, uv, key_medium, key_bright);
  EXPECT_EQ(marked, (std::vector<bool>{true, true, false, false, false, false, false}));
}

TEST(BandCrossings, FacesWithTheObjectsTextureAreWrittenWithoutAnIndex) {
  SceneMesh mesh;
  mesh.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
  mesh.normals.assign(4, Vec3(0, 0, -1));
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.max = Vec3(1, 1, 0);
  FaceTextures textures;
  textures.names = {"Two"};
  textures.index = {FaceTextures::object_texture, 0};
  std::string text;
  append_mesh2(text, "M", mesh, std::vector<TextureCoordinate>(4, at(0.5)), &textures);
  EXPECT_NE(text.find("texture_list { 1, texture { Two } }"), std::string::npos) << text;
  EXPECT_NE(text.find("<0,1,2>, <0,2,3>,0\n"), std::string::npos) << text;

  textures.index = {1, 0};  // a texture not in the list
  EXPECT_THROW(append_mesh2(text, "M", mesh, {}, &textures), std::logic_error);
}

}  // namespace
}  // namespace toonwater::test
