// Secondary particles (analyzer/particles.hpp): FLIP Fluids' whitewater files read back exactly
// and refused when damaged; OpenVDB point grids in their world coordinates; and Mantaflow's
// particle cache of the shared dam break, whose counts per kind and frame must be those its
// README lists, in the places its README says (bubbles under the surface, spray above it).
#include "analyzer/mesh_reader.hpp"
#include "analyzer/particles.hpp"
#include "tests/support/largest_allocation.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <regex>
#include <string>
#include <vector>

namespace toonwater::test {
namespace {

namespace fs = std::filesystem;

std::string error_of(const fs::path& path) {
  try {
    read_particles(path);
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.rfind(path.string() + ": ", 0), 0u) << message;
    return message;
  }
  ADD_FAILURE() << "no error for " << path;
  return {};
}

TEST(Particles, WhitewaterFilesReadBackWithTheirKindFromTheName) {
  ScratchDir dir;
  const std::vector<std::pair<int, Vec3>> foam{
      {200, {0.5, 0.25, -1}}, {3, {1, 2, 3}}, {3, {-0.125, 0, 4}}, {0, {7, 8, 9}}};
  write_text(dir / "foam000012.wwp", wwp_bytes(foam));
  const ParticleSet set = read_particles(dir / "foam000012.wwp");
  ASSERT_EQ(set.positions.size(), 4u);
  EXPECT_EQ(set.positions[0], Vec3(7, 8, 9));  // sorted by id, as the file holds them
  EXPECT_EQ(set.positions[1], Vec3(1, 2, 3));
  EXPECT_EQ(set.positions[2], Vec3(-0.125, 0, 4));
  EXPECT_EQ(set.positions[3], Vec3(0.5, 0.25, -1));
  EXPECT_EQ(count_of(set, ParticleKind::foam), 4u);
  EXPECT_TRUE(set.velocities.empty());

  for (const auto& [name, kind] :
       std::vector<std::pair<std::string, ParticleKind>>{{"bubble000001.wwp", ParticleKind::bubble},
                                                         {"SPRAY000002.WWP", ParticleKind::spray},
                                                         {"dust000003.wwp", ParticleKind::dust}}) {
    write_text(dir / name, wwp_bytes({{1, {0, 0, 0}}}));
    EXPECT_EQ(count_of(read_particles(dir / name), kind), 1u) << name;
  }
  write_text(dir / "spray000004.wwp", "");  // the engine writes nothing for no particles
  EXPECT_TRUE(read_particles(dir / "spray000004.wwp").positions.empty());
}

TEST(Particles, DamagedWhitewaterFilesAreOneLineErrors) {
  ScratchDir dir;
  const std::string whole = wwp_bytes({{0, {1, 2, 3}}, {9, {4, 5, 6}}});
  for (std::size_t size = 1; size < whole.size(); ++size) {
    write_text(dir / "foam000001.wwp", whole.substr(0, size));
    error_of(dir / "foam000001.wwp");
  }
  write_text(dir / "foam000002.wwp", whole + "x");
  EXPECT_NE(error_of(dir / "foam000002.wwp").find("promise 2 particles"), std::string::npos);

  std::string decreasing = whole;
  const std::uint32_t five = 5;
  std::memcpy(decreasing.data() + 4 * 3, &five, 4);
  write_text(dir / "foam000003.wwp", decreasing);
  EXPECT_NE(error_of(dir / "foam000003.wwp").find("not a whitewater file"), std::string::npos);

  write_text(dir / "foam000004.wwp",
             wwp_bytes({{0, {1, std::numeric_limits<double>::quiet_NaN(), 3}}}));
  EXPECT_NE(error_of(dir / "foam000004.wwp").find("NaN or infinite (particle 0)"),
            std::string::npos);

  for (const std::string name :
       {"whitewater.wwp", "foam.wwp", "foam12a.wwp", "seafoam000001.wwp", "000001.wwp"}) {
    write_text(dir / name, whole);
    EXPECT_NE(error_of(dir / name).find("name says its kind"), std::string::npos) << name;
  }
  write_text(dir / "foam000005.xyz", whole);
  EXPECT_NE(error_of(dir / "foam000005.xyz").find("unknown particle format"), std::string::npos);
  error_of(dir / "missing000001.wwp");

  // A table that promises 2^32 − 1 particles of a 1 kB file: refused before any allocation.
  std::string huge(1024, '\0');
  const std::uint32_t most = 0xFFFFFFFEu;
  for (int id = 0; id < 256; ++id) std::memcpy(huge.data() + 4 * id, &most, 4);
  write_text(dir / "foam000006.wwp", huge);
  reset_largest_allocation();
  EXPECT_NE(error_of(dir / "foam000006.wwp").find("promise 4294967295 particles"),
            std::string::npos);
  EXPECT_LT(largest_allocation(), std::size_t{1} << 20);
}

// tests/analyzer/data (README there): three points written by OpenVDB 10 with a NullCodec
// position attribute in a transform of voxel 0.25, and a file whose only grid is the float
// grid 'phi'. Fixtures rather than written here: OpenVDB's point conversion templates would
// take most of this file's compile time, in the normal and the sanitizer builds alike.
TEST(Particles, APointGridThatIsNotMantaflowsKeepsItsWorldCoordinates) {
  const fs::path data = fs::path(TOONWATER_SOURCE_DIR) / "tests/analyzer/data";
  const std::vector<Vec3> points{{0.1, 0.2, 0.3}, {-1.5, 2.25, 0.75}, {3, -4, 5}};
  const ParticleSet set = read_particles(data / "three_points.vdb");
  ASSERT_EQ(set.positions.size(), points.size());
  std::vector<Vec3> read = set.positions;
  std::vector<Vec3> expected = points;
  const auto less = [](const Vec3& a, const Vec3& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  };
  std::sort(read.begin(), read.end(), less);
  std::sort(expected.begin(), expected.end(), less);
  for (std::size_t i = 0; i < read.size(); ++i)
    EXPECT_LT((read[i] - expected[i]).norm(), 1e-6) << i;
  EXPECT_EQ(count_of(set, ParticleKind::other), points.size());

  EXPECT_NE(error_of(data / "phi_only.vdb").find("no point grid; its grids: 'phi'"),
            std::string::npos);
}

// The README's per-frame table: frame -> {spray, foam, bubbles}, for the frames whose particle
// files the data keeps (counts without brackets).
std::map<long, std::array<std::size_t, 3>> readme_counts(const fs::path& readme) {
  std::ifstream in(readme);
  std::map<long, std::array<std::size_t, 3>> counts;
  const std::regex row(R"(^\| (\d+) \|[^|]*\|[^|]*\|[^|]*\|[^|]*\| (\d+) \| (\d+) \| (\d+) \|)");
  std::string line;
  std::smatch m;
  while (std::getline(in, line))
    if (std::regex_search(line, m, row))
      counts[std::stol(m[1])] = {std::stoul(m[2]), std::stoul(m[3]), std::stoul(m[4])};
  return counts;
}

// Where Mantaflow's normalised coordinates put the dam break's world (its README): the domain
// [−0.6, 0.6] × [−0.3, 0.3] × [0, 0.6], longest side 1.2, centre (0, 0, 0.3).
Vec3 dambreak_world(const Vec3& normalised) { return 1.2 * normalised + Vec3(0, 0, 0.3); }
constexpr double cell = 0.01875;  // the bake's voxel

// The height of the water's highest face above each 1 cm column of the tank.
class SurfaceHeight {
 public:
  explicit SurfaceHeight(const TriangleMesh& water) : top_(cells_x * cells_y, -1.0) {
    for (const Triangle& t : water.triangles) {
      Vec3 lo = water.positions[t[0]], hi = lo;
      for (const std::int32_t v : t) {
        lo = lo.cwiseMin(water.positions[v]);
        hi = hi.cwiseMax(water.positions[v]);
      }
      for (int i = column(lo.x(), 0.6, cells_x); i <= column(hi.x(), 0.6, cells_x); ++i)
        for (int j = column(lo.y(), 0.3, cells_y); j <= column(hi.y(), 0.3, cells_y); ++j)
          top_[static_cast<std::size_t>(j * cells_x + i)] =
              std::max(top_[static_cast<std::size_t>(j * cells_x + i)], hi.z());
    }
  }
  double at(const Vec3& p) const {
    return top_[static_cast<std::size_t>(column(p.y(), 0.3, cells_y) * cells_x +
                                         column(p.x(), 0.6, cells_x))];
  }

 private:
  static constexpr int cells_x = 120, cells_y = 60;
  static int column(double coordinate, double half_width, int cells) {
    return std::clamp(static_cast<int>((coordinate + half_width) * 100.0), 0, cells - 1);
  }
  std::vector<double> top_;
};

TEST(Particles, MantaflowDambreakCountsAndPlacesEveryKind) {
  const fs::path shared = shared_dir();
  if (shared.empty()) GTEST_SKIP() << "../shared/data is absent: real-data test skipped";
  const fs::path data = shared / "data/mantaflow-dambreak";
  const auto counts = readme_counts(data / "README.md");
  std::size_t frames = 0;
  for (const auto& [frame, expected] : counts) {
    char name[64];
    std::snprintf(name, sizeof name, "cache/particles/fluid_particles_%04ld.vdb", frame);
    if (!fs::exists(data / name)) continue;
    ++frames;
    const ParticleSet set = read_particles(data / name);
    EXPECT_EQ(count_of(set, ParticleKind::spray), expected[0]) << frame;
    EXPECT_EQ(count_of(set, ParticleKind::foam), expected[1]) << frame;
    EXPECT_EQ(count_of(set, ParticleKind::bubble), expected[2]) << frame;
    EXPECT_EQ(count_of(set, ParticleKind::other), 0u) << frame;
    ASSERT_EQ(set.velocities.size(), set.positions.size()) << frame;
    for (const Vec3& p : set.positions) {
      const Vec3 w = dambreak_world(p);  // within the domain, give or take a cell
      ASSERT_TRUE(w.x() > -0.62 && w.x() < 0.62 && w.y() > -0.32 && w.y() < 0.32 && w.z() > -0.02 &&
                  w.z() < 0.62)
          << frame << ": " << w.transpose();
    }
    if (frame % 5 != 0) continue;
    // How deep under the water's surface each kind lies, in cells (the README measures the
    // same with phi: bubbles deepest, foam just under the surface, spray at it and above it).
    char water_name[32];
    std::snprintf(water_name, sizeof water_name, "water_%04ld.obj", frame);
    const SurfaceHeight surface(read_mesh(data / water_name).mesh);
    std::array<std::vector<double>, 3> depth;  // spray, foam, bubble
    std::size_t spray_over = 0;
    for (std::size_t i = 0; i < set.positions.size(); ++i) {
      const Vec3 w = dambreak_world(set.positions[i]);
      const double cells_under = (surface.at(w) - w.z()) / cell;
      const auto k = static_cast<std::size_t>(set.kinds[i]);  // spray, foam, bubble: 0, 1, 2
      if (k < 3) depth[k].push_back(cells_under);
      spray_over += set.kinds[i] == ParticleKind::spray && cells_under < 0;
    }
    std::array<double, 3> median{};
    for (std::size_t k = 0; k < 3; ++k) {
      ASSERT_FALSE(depth[k].empty()) << frame;
      std::nth_element(depth[k].begin(), depth[k].begin() + depth[k].size() / 2, depth[k].end());
      median[k] = depth[k][depth[k].size() / 2];
    }
    std::printf(
        "frame %ld: median cells under the surface: spray %.2f, foam %.2f, bubbles %.2f; "
        "spray over it %zu\n",
        frame, median[0], median[1], median[2], spray_over);
    EXPECT_LT(median[0], median[1]) << frame;
    EXPECT_LT(median[1], median[2]) << frame;
    EXPECT_GT(median[2], 1.0) << frame << ": bubbles are in the water";
    EXPECT_GT(spray_over, 0u) << frame << ": some spray is in the air";
  }
  EXPECT_EQ(frames, 24u) << "particle files of frames 1-24 with counts in the README";
}

}  // namespace
}  // namespace toonwater::test
