// The texture each face of the water needs (scene/band_crossings.hpp), and how the mesh2 writer
// gives it.
#include "scene/band_crossings.hpp"

#include "scene/mesh2_writer.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace toonwater::test {
namespace {

const ToonLimits three_bands{{0.4, 0.6}, std::nullopt};
const ToonLimits three_bands_and_regions{{0.4, 0.6}, std::pair(0.38, 0.62)};

TextureCoordinate at(double u) { return {static_cast<float>(u), 0.5F}; }

TEST(BandCrossings, AFaceOfDarkAndBrightCornersNoneMediumHasTwoBands) {
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
  using enum FaceBands;
  EXPECT_EQ(face_bands(faces, uv, three_bands),
            (std::vector<FaceBands>{two, two, three, three, three, three, three}));
}

// Region corners (v beyond the flow keys 0.38 and 0.62) hide their u: a face across a region's
// edge whose band corners lie in one band is drawn in that band alone, whatever the region
// corner's u; with dark and bright band corners, in two bands. Where regions are not drawn,
// v means nothing.
TEST(BandCrossings, AFaceAcrossARegionsEdgeIsDrawnInItsBandCornersBand) {
  auto corner = [](double u, double v) {
    return TextureCoordinate{static_cast<float>(u), static_cast<float>(v)};
  };
  const std::vector<TextureCoordinate> uv{
      corner(0.1, 0.9),   // 0: ridge, dark u
      corner(0.9, 0.1),   // 1: valley, bright u
      corner(0.5, 0.5),   // 2: medium
      corner(0.55, 0.5),  // 3: medium
      corner(0.9, 0.5),   // 4: bright
      corner(0.1, 0.5),   // 5: dark
  };
  const std::vector<Triangle> faces{
      {0, 2, 3},  // ridge, medium, medium
      {1, 4, 4},  // valley, bright
      {0, 5, 2},  // ridge, dark, medium: two band corners' bands
      {0, 5, 4},  // ridge, dark, bright
      {0, 1, 2},  // ridge, valley, medium
      {0, 0, 1},  // regions only
  };
  using enum FaceBands;
  EXPECT_EQ(face_bands(faces, uv, three_bands_and_regions),
            (std::vector<FaceBands>{only_medium, only_bright, three, two, only_medium, three}));
  EXPECT_EQ(face_bands(faces, uv, three_bands),
            (std::vector<FaceBands>{three, three, three, two, three, two}));
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
