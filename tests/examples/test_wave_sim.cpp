// The examples' wave simulation: the physics it claims and the frames it writes.
#include "analyzer/mesh_reader.hpp"
#include "sim/body_displacement.hpp"
#include "sim/mesh_builders.hpp"
#include "sim/scenarios.hpp"
#include "sim/water_figure.hpp"
#include "sim/wave_scene.hpp"
#include "sim/wave_solver.hpp"
#include "tests/support/run_toonwater.hpp"
#include "tests/support/test_support.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>

namespace toonwater::sim {
namespace {

using test::ScratchDir;

HeightField gaussian_hump(double amplitude, double sigma, double cx = 0, double cz = 0) {
  HeightField f = make_height_field(-2, 2, -2, 2, 128);
  for (int j = 0; j < f.nz; ++j)
    for (int i = 0; i < f.nx; ++i) {
      const double r2 = std::pow(f.x(i) - cx, 2) + std::pow(f.z(j) - cz, 2);
      f.height[f.index(i, j)] = amplitude * std::exp(-r2 / (2 * sigma * sigma));
    }
  return f;
}

double run_steps(HeightField& f, const WaveParameters& p, double duration) {
  const auto damping = damping_per_node(f, p);
  const int steps = static_cast<int>(std::ceil(duration / stable_time_step(f, p)));
  for (int k = 0; k < steps; ++k) step_wave(f, p, damping, duration / steps);
  return duration;
}

// Linear interpolation of the height at (x, z).
double height_at(const HeightField& f, double x, double z) {
  const double u = (x - f.x0) / f.spacing, v = (z - f.z0) / f.spacing;
  const int i = std::clamp(static_cast<int>(u), 0, f.nx - 2);
  const int j = std::clamp(static_cast<int>(v), 0, f.nz - 2);
  const double a = u - i, b = v - j;
  return (1 - a) * (1 - b) * f.height[f.index(i, j)] + a * (1 - b) * f.height[f.index(i + 1, j)] +
         (1 - a) * b * f.height[f.index(i, j + 1)] + a * b * f.height[f.index(i + 1, j + 1)];
}

TEST(WaveSolver, EnergyIsKeptWithoutDampingAndDecaysWithIt) {
  const WaveParameters free{.wave_speed = 1.0};
  HeightField f = gaussian_hump(0.05, 0.15);
  const double e0 = wave_energy(f, free);
  ASSERT_GT(e0, 0);
  run_steps(f, free, 1.0);  // the ring stays inside the box: no walls involved
  EXPECT_NEAR(wave_energy(f, free) / e0, 1.0, 0.03);

  const WaveParameters damped{.wave_speed = 1.0, .damping = 0.5};
  HeightField g = gaussian_hump(0.05, 0.15);
  double previous = wave_energy(g, damped);
  for (int k = 0; k < 4; ++k) {
    run_steps(g, damped, 0.25);
    const double e = wave_energy(g, damped);
    EXPECT_LT(e, previous);
    previous = e;
  }
  // Energy decays about like exp(−γt) (γ damps the kinetic half: between exp(−γt) and 1).
  EXPECT_LT(previous / e0, std::exp(-0.5 * 1.0 * 0.5) * 1.03);
  EXPECT_GT(previous / e0, std::exp(-0.5 * 1.0) * 0.97);
}

TEST(WaveSolver, ViscosityRemovesShortWavesFasterThanLongOnes) {
  const WaveParameters p{.wave_speed = 1.0, .viscosity = 0.004};
  HeightField broad = gaussian_hump(0.05, 0.3), narrow = gaussian_hump(0.05, 0.05);
  const double e_broad = wave_energy(broad, p), e_narrow = wave_energy(narrow, p);
  run_steps(broad, p, 0.5);
  run_steps(narrow, p, 0.5);
  EXPECT_LT(wave_energy(narrow, p) / e_narrow, 0.8 * wave_energy(broad, p) / e_broad);
}

TEST(WaveSolver, WavesTravelAtTheWaveSpeed) {
  const WaveParameters p{.wave_speed = 0.8};
  HeightField f = gaussian_hump(0.05, 0.08);
  run_steps(f, p, 1.0);
  // The ring's crest is at radius c·t: find the radius of the largest height along +x.
  double best_r = 0, best_h = -1;
  for (double r = 0.3; r < 1.5; r += 0.005) {
    const double h = height_at(f, r, 0.0);
    if (h > best_h) best_h = h, best_r = r;
  }
  EXPECT_NEAR(best_r, 0.8, 0.06);
}

TEST(WaveSolver, RejectsUnstableSteps) {
  HeightField f = gaussian_hump(0.05, 0.1);
  const WaveParameters p{.wave_speed = 1.0};
  EXPECT_THROW(step_wave(f, p, damping_per_node(f, p), 2 * stable_time_step(f, p)),
               std::invalid_argument);
}

TEST(WaveSolver, SpongeAbsorbsWhatWallsReflect) {
  const WaveParameters walls{.wave_speed = 1.0};
  const WaveParameters sponge{.wave_speed = 1.0, .sponge_width = 0.5, .sponge_damping = 10.0};
  HeightField a = gaussian_hump(0.05, 0.1), b = gaussian_hump(0.05, 0.1);
  const double e0 = wave_energy(a, walls);
  run_steps(a, walls, 3.0);  // the ring reaches the walls at t ≈ 2 and comes back
  run_steps(b, sponge, 3.0);
  EXPECT_GT(wave_energy(a, walls), 0.9 * e0);
  EXPECT_LT(wave_energy(b, sponge), 0.1 * e0);
}

TEST(SphereDisplacement, IsTheSubmergedThicknessAndItsVolume) {
  HeightField f = make_height_field(-1, 1, -1, 1, 200);
  const double r = 0.3;
  auto volume = [&](const Vec3& c) {
    double v = 0;
    for (double d : sphere_displacement(f, c, r)) v += d * f.spacing * f.spacing;
    return v;
  };
  const double sphere = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  EXPECT_NEAR(volume(Vec3(0, 0, 0)), 0.5 * sphere, 0.01 * sphere);  // half submerged
  EXPECT_NEAR(volume(Vec3(0, -1, 0)), sphere, 0.01 * sphere);       // fully under
  EXPECT_EQ(volume(Vec3(0, 0.31, 0)), 0.0);                         // above the water
  // Over the centre of a half-submerged sphere the thickness is the radius.
  EXPECT_NEAR(sphere_displacement(f, Vec3(0, 0, 0), r)[f.index(100, 100)], r, 1e-12);
}

// The wake example: the sphere runs faster than the waves (1.5 c), so the water it pushes
// piles up on its front half — the bow wave — and spreads sideways, a trough opens behind it,
// and the water ahead stays calm (no wave outruns a supercritical body). The wake behind is
// mirror-symmetric about the path.
TEST(WakeScenario, BowWaveAtTheFrontTroughBehindCalmAhead) {
  HeightField last;
  Vec3 centre;
  WaveScene s;
  s.field = make_height_field(-2.0, 2.0, -1.0, 1.0, 128);
  s.waves = {.wave_speed = 1.0,
             .damping = 0.3,
             .sponge_width = 0.4,
             .sponge_damping = 8.0,
             .viscosity = 0.006};
  s.sphere = MovingSphere{[](double t) { return Vec3(-2.0 + 1.5 * t, 0.0, 0.0); }, 0.22, 0.7};
  s.record_start = 1.6;
  s.record_end = 1.6;
  run_wave_scene(s, 1, [&](int, double t, const HeightField& f) {
    last = f;
    centre = s.sphere->centre(t);
  });
  const double r = 0.22;
  EXPECT_GT(height_at(last, centre.x() + 0.5 * r, 0.0), 0.3 * r);   // bow wave
  EXPECT_GT(height_at(last, centre.x(), 1.4 * r), 0.3 * r);         // beside, outside the hull
  EXPECT_LT(height_at(last, centre.x() - 1.1 * r, 0.0), -0.3 * r);  // trough behind
  for (double x = centre.x() + 1.5 * r; x < 1.5; x += 0.05)
    EXPECT_LT(std::abs(height_at(last, x, 0.0)), 1e-3) << "x = " << x;
  // Wake: behind the sphere the water moves on both sides, mirror-symmetric about z = 0.
  double disturbed = 0, asymmetry = 0;
  for (double x = centre.x() - 1.2; x < centre.x() - r; x += 0.05)
    for (double z = 0.05; z < 0.9; z += 0.05) {
      const double a = height_at(last, x, z), b = height_at(last, x, -z);
      disturbed += std::abs(a);
      asymmetry += std::abs(a - b);
    }
  EXPECT_GT(disturbed, 0);
  EXPECT_LT(asymmetry, 1e-9 * disturbed + 1e-12);
}

// The drop example: the ripples are circles around the drop, on a grid that is not round.
TEST(DropScenario, RipplesAreCircular) {
  std::map<int, TriangleMesh> water;
  simulate(
      {"drop", 3, 128},
      [&](const std::string& name, const TriangleMesh& m) {
        if (name.starts_with("water_")) water[std::stoi(name.substr(6, 4))] = m;
      },
      [](int, int) {});
  ASSERT_EQ(water.size(), 3u);
  // Frame 2 (t = 0.9 s): rings of radius below 0.9, inside the pool's walls (1.0 away).
  // The mesh's vertices are the grid's nodes, in order.
  HeightField f = make_height_field(-1.6, 1.6, -1.0, 1.0, 128);
  ASSERT_EQ(water[2].positions.size(), f.height.size());
  for (std::size_t n = 0; n < f.height.size(); ++n) f.height[n] = water[2].positions[n].y();
  // On circles around the drop the height hardly depends on the direction.
  double amplitude = 0, worst_spread = 0;
  for (double rho = 0.3; rho < 0.85; rho += 0.02) {
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 72; ++k) {
      const double angle = 2 * std::numbers::pi * k / 72;
      const double h = height_at(f, rho * std::cos(angle), rho * std::sin(angle));
      lo = std::min(lo, h), hi = std::max(hi, h);
    }
    amplitude = std::max({amplitude, std::abs(lo), std::abs(hi)});
    worst_spread = std::max(worst_spread, hi - lo);
  }
  ASSERT_GT(amplitude, 5e-3);
  EXPECT_LT(worst_spread, 0.1 * amplitude);
  // Frame 1 (t = 0.3 s): the ball is still in the air and the water at rest.
  for (const Vec3& p : water[1].positions) ASSERT_EQ(p.y(), 0.0);
}

TEST(MeshBuilders, SolidsAreClosedAndOutward) {
  auto signed_volume = [](const TriangleMesh& m) {
    double v = 0;
    for (const Triangle& t : m.triangles)
      v += m.positions[t[0]].dot(m.positions[t[1]].cross(m.positions[t[2]])) / 6.0;
    return v;
  };
  auto closed = [](const TriangleMesh& m) {
    std::map<std::pair<int, int>, int> edges;  // directed edges: each once, its twin once
    for (const Triangle& t : m.triangles)
      for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
    for (const auto& [e, n] : edges)
      if (n != 1 || !edges.count({e.second, e.first})) return false;
    return true;
  };
  const double pi = std::numbers::pi;
  const TriangleMesh sphere = uv_sphere(Vec3(1, 2, 3), 0.5, 24, 48);
  EXPECT_TRUE(closed(sphere));
  EXPECT_NEAR(signed_volume(sphere), 4.0 / 3.0 * pi * 0.125, 0.02 * 4.0 / 3.0 * pi * 0.125);
  const TriangleMesh cap = capsule(Vec3(0, 0, 0), Vec3(1, 1, 0), 0.1, 24);
  EXPECT_TRUE(closed(cap));
  const double cap_volume = pi * 0.01 * std::sqrt(2.0) + 4.0 / 3.0 * pi * 0.001;
  EXPECT_NEAR(signed_volume(cap), cap_volume, 0.05 * cap_volume);
  EXPECT_TRUE(closed(water_figure_body(0.3, 48)));
  EXPECT_GT(signed_volume(water_figure_body(0.3, 48)), 0);
}

TEST(MeshBuilders, HeightFieldSheetFacesUp) {
  HeightField f = make_height_field(-1, 1, -0.5, 0.5, 16);
  const TriangleMesh m = height_field_mesh(f);
  EXPECT_EQ(m.positions.size(), static_cast<std::size_t>(17 * 9));
  EXPECT_EQ(m.triangles.size(), static_cast<std::size_t>(2 * 16 * 8));
  for (const Triangle& t : m.triangles) {
    const Vec3 n =
        (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
    ASSERT_GT(n.y(), 0);
  }
}

// Every bone point lies inside the body in every frame: the figure is fully under water.
TEST(WaterFigure, BonesStayInsideTheBody) {
  const TriangleMesh bones = water_figure_bones(48);
  for (double t = 0; t < water_figure_period(); t += water_figure_period() / 8) {
    const TriangleMesh body = water_figure_body(t, 96);
    for (const Vec3& bone : bones.positions) {
      // Moved off the mesh's meridian planes, so the ray meets no edge exactly.
      const Vec3 p = bone + Vec3(1.3e-7, 0, 1.7e-7);
      // Inside a closed mesh: a ray along +y crosses it an odd number of times.
      int crossings = 0;
      for (const Triangle& tri : body.triangles) {
        const Vec3 &a = body.positions[tri[0]], &b = body.positions[tri[1]],
                   &c = body.positions[tri[2]];
        auto side = [&](const Vec3& u, const Vec3& v) {
          return (u.x() - p.x()) * (v.z() - p.z()) - (u.z() - p.z()) * (v.x() - p.x());
        };
        const double s1 = side(a, b), s2 = side(b, c), s3 = side(c, a);
        if (!((s1 > 0 && s2 > 0 && s3 > 0) || (s1 < 0 && s2 < 0 && s3 < 0))) continue;
        const Vec3 n = (b - a).cross(c - a);
        const double y = a.y() - (n.x() * (p.x() - a.x()) + n.z() * (p.z() - a.z())) / n.y();
        if (y > p.y()) ++crossings;
      }
      ASSERT_EQ(crossings % 2, 1) << "bone point " << p.transpose() << " at t = " << t;
    }
  }
}

// The simulate command: names and counts of the files, meshes that read back as written.
TEST(SimulateCommand, WritesNumberedFramesAndStaticObjects) {
  ScratchDir dir;
  auto r = test::run_toonwater(
      {"simulate", "wake", "--frames", "3", "--resolution", "32", "--out", (dir / "sim").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (int k = 1; k <= 3; ++k) {
    const InputMesh water = read_mesh(dir / "sim" / frame_file_name("water", k));
    EXPECT_EQ(water.mesh.positions.size(), 33u * 17u);
    EXPECT_TRUE(std::filesystem::exists(dir / "sim" / frame_file_name("sphere", k)));
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "sim" / "water_0004.obj"));

  r = test::run_toonwater({"simulate", "reflection", "--frames", "2", "--resolution", "32", "--out",
                           (dir / "refl").string()});
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_mesh(dir / "refl" / "left_ball.obj").mesh.positions.size(),
            read_mesh(dir / "refl" / "right_ball.obj").mesh.positions.size());
  std::size_t files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir / "refl")) ++files;
  EXPECT_EQ(files, 4u);  // two water frames, two static balls, nothing else (no temporaries)

  // Deterministic: the same request writes the same bytes.
  ScratchDir again;
  ASSERT_EQ(test::run_toonwater({"simulate", "wake", "--frames", "3", "--resolution", "32", "--out",
                                 (again / "sim").string()})
                .exit_code,
            0);
  EXPECT_EQ(test::read_text(dir / "sim" / "water_0003.obj"),
            test::read_text(again / "sim" / "water_0003.obj"));
}

TEST(SimulateCommand, RejectsUnknownScenarioAndBadCounts) {
  ScratchDir dir;
  auto r = test::run_toonwater({"simulate", "tsunami", "--out", dir.path().string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_NE(r.output.find("tsunami"), std::string::npos) << r.output;
  r = test::run_toonwater({"simulate", "wake", "--frames", "0", "--out", dir.path().string()});
  EXPECT_NE(r.exit_code, 0);
  EXPECT_TRUE(std::filesystem::is_empty(dir.path()));
}

}  // namespace
}  // namespace toonwater::sim
