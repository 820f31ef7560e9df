// Affine transforms of input meshes: points map as the 3×4 matrix says, mirrors keep normals
// pointing out, and NaN, infinite or singular maps are refused — scale-free, so a tiny uniform
// scale is still accepted. Also the analyze options that build them.
#include "analyzer/affine_transform.hpp"
#include "analyzer/mesh_reader.hpp"

#include "corpus/analytic_surfaces.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace toonwater {
namespace {

// Six times the signed volume enclosed by a closed mesh: positive when its triangles wind
// counter-clockwise seen from outside (normals pointing out).
double six_volume(const TriangleMesh& mesh) {
  double sum = 0;
  for (const Triangle& t : mesh.triangles)
    sum += mesh.positions[t[0]].dot(mesh.positions[t[1]].cross(mesh.positions[t[2]]));
  return sum;
}

std::string message_of(const std::array<double, 12>& rows) {
  try {
    affine_from_rows(rows);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(AffineTransform, RowsAreTheMatrixAndItsTranslation) {
  const AffineTransform t = affine_from_rows(std::array<double, 12>{0, -2, 0, 10,  //
                                                                    1, 0, 0, 20,   //
                                                                    0, 0, 3, 30});
  TriangleMesh mesh{{Vec3(1, 2, 3)}, {}};
  apply_transform(t, mesh, "t.obj");
  EXPECT_EQ(mesh.positions[0], Vec3(-4 + 10, 1 + 20, 9 + 30));

  TriangleMesh scaled{{Vec3(1, 2, 3), Vec3(-0.5, 0, 0.25)}, {}};
  apply_transform(scale_then_translate(2, Vec3(1, -2, 0.5)), scaled, "scaled.obj");
  EXPECT_EQ(scaled.positions[0], Vec3(3, 2, 6.5));
  EXPECT_EQ(scaled.positions[1], Vec3(0, -2, 1));
}

TEST(AffineTransform, APositionThatOverflowsIsAnInputErrorNamingTheFileAndVertex) {
  // Each entry of the map and each coordinate is finite; the mapped position is not.
  TriangleMesh mesh{{Vec3(0, 1, 0), Vec3(0, 1e300, 0), Vec3(1e300, 0, 0)}, {Triangle{0, 1, 2}}};
  try {
    apply_transform(scale_then_translate(1e10, Vec3::Zero()), mesh, "frame_0001.obj");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              "frame_0001.obj: vertex 1 lies beyond the largest double after the transform");
  }
  TriangleMesh shifted{{Vec3(-1.5e308, 0, 0)}, {}};
  EXPECT_THROW(apply_transform(scale_then_translate(1, Vec3(-1e308, 0, 0)), shifted, "a.obj"),
               InputError);
}

TEST(AffineTransform, MirrorsReverseTheWindingSoNormalsStillPointOut) {
  const TriangleMesh sphere = make_icosphere(2).mesh;
  ASSERT_GT(six_volume(sphere), 0);
  const std::vector<AffineTransform> maps{
      affine_from_rows(std::array<double, 12>{-1, 0, 0, 5, 0, 1, 0, 0, 0, 0, 1, 0}),  // x mirror
      affine_from_rows(std::array<double, 12>{0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 2, 0}),   // swap x, y
      scale_then_translate(-3, Vec3(1, 2, 3)),  // through a point
      affine_from_rows(std::array<double, 12>{0, -1, 0, 0, 1, 0, 0, 0, 0, 0, 1, 0})};  // rotation
  for (std::size_t m = 0; m < maps.size(); ++m) {
    TriangleMesh mesh = sphere;
    apply_transform(maps[m], mesh, "sphere.obj");
    EXPECT_GT(six_volume(mesh), 0) << "map " << m;
    const Triangle& t = sphere.triangles[0];
    const Triangle expected = maps[m].linear.determinant() < 0 ? Triangle{t[0], t[2], t[1]} : t;
    EXPECT_EQ(mesh.triangles[0], expected) << "map " << m;
  }
}

TEST(AffineTransform, NonFiniteAndSingularMapsAreRefused) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_NE(message_of({1, 0, 0, 0, 0, nan, 0, 0, 0, 0, 1, 0}).find("NaN or infinite"),
            std::string::npos);
  EXPECT_NE(message_of({1, 0, 0, inf, 0, 1, 0, 0, 0, 0, 1, 0}).find("NaN or infinite"),
            std::string::npos);
  // Rank 2: the third row is the sum of the first two — the mesh would be flattened.
  EXPECT_NE(message_of({1, 2, 3, 0, 4, 5, 6, 0, 5, 7, 9, 0}).find("singular"), std::string::npos);
  EXPECT_NE(message_of({1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 7}).find("singular"), std::string::npos);
  // Nearly dependent rows (the third leaves the plane of the other two by 1e-14 of its length):
  // singular whatever the scale.
  EXPECT_NE(message_of({1e6, 0, 0, 0, 0, 1e6, 0, 0, 1e6, 1e6, 1e-8, 0}).find("singular"),
            std::string::npos);
  EXPECT_THROW(scale_then_translate(0, Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(scale_then_translate(nan, Vec3::Zero()), std::invalid_argument);
  EXPECT_THROW(scale_then_translate(1, Vec3(0, inf, 0)), std::invalid_argument);
  // Scale-free: micrometre and kilometre scales are fine.
  EXPECT_NO_THROW(scale_then_translate(1e-6, Vec3::Zero()));
  EXPECT_NO_THROW(scale_then_translate(1e6, Vec3(1e6, 0, 0)));
  // det A overflows or underflows here, but the maps are exact: not singular.
  EXPECT_NO_THROW(scale_then_translate(1e300, Vec3::Zero()));
  EXPECT_NO_THROW(scale_then_translate(1e-150, Vec3::Zero()));
  EXPECT_THROW(
      affine_from_rows(std::array<double, 12>{1e200, 0, 0, 0, 1e200, 0, 0, 0, 0, 0, 1e200, 0}),
      std::invalid_argument);  // rows 0 and 1 alike, however large
}

TEST(AffineTransform, ATinyMirrorStillReversesTheWinding) {
  // det = −1e-450 underflows to −0: the sign must come from the map, not from det A.
  TriangleMesh mesh{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {Triangle{0, 1, 2}}};
  apply_transform(scale_then_translate(-1e-150, Vec3::Zero()), mesh, "tiny.obj");
  EXPECT_EQ(mesh.triangles[0], (Triangle{0, 2, 1}));
}

TEST(AffineTransformCli, BadTransformsAreOneLineErrorsBeforeTheMeshIsRead) {
  const test::ScratchDir dir;
  const std::string missing = (dir / "missing.obj").string();
  struct Case {
    std::vector<std::string> options;
    std::string expected;
  };
  const std::vector<Case> cases{
      {{"--transform", "1,0,0,0,0,1,0,0,0,0,0,0"}, "singular"},
      {{"--scale", "0"}, "singular"},
      {{"--scale", "nan"}, "--scale: 'nan' is not a finite number"},
      {{"--transform", "1,0,0,0,0,1,0,0,0,0,1"}, "--transform"},
      {{"--translate", "1,2"}, "--translate"},
      {{"--transform", "1,0,0,0,0,1,0,0,0,0,1,0", "--scale", "2"}, "excludes"}};
  for (const Case& c : cases) {
    std::vector<std::string> args{"analyze", missing};
    args.insert(args.end(), c.options.begin(), c.options.end());
    const test::CommandResult r = test::run_toonwater(args);
    EXPECT_NE(r.exit_code, 0) << c.expected;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find("missing.obj"), std::string::npos) << "checked first: " << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
  }
}

TEST(AffineTransformCli, ATransformThatOverflowsTheMeshIsBadInputAndWritesNothing) {
  const test::ScratchDir dir;
  const std::filesystem::path mesh = dir / "far.obj", csv = dir / "far.csv";
  test::write_text(mesh, "v 1e300 0 0\nv 0 1e300 0\nv 0 0 1e300\nf 1 2 3\n");
  const test::CommandResult r =
      test::run_toonwater({"analyze", mesh.string(), "--scale", "1e10", "--csv", csv.string()});
  EXPECT_EQ(r.exit_code, 2) << r.output;
  EXPECT_NE(r.output.find(mesh.string() + ": vertex 0 lies beyond the largest double"),
            std::string::npos)
      << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
  EXPECT_FALSE(std::filesystem::exists(csv));
}

}  // namespace
}  // namespace toonwater
