// povgen speed: a 55k-vertex frame analysed and written (target <= 0.1 s), a
// 1M-vertex mesh2 written (target <= 0.5 s), and POV-Ray's own parse and trace times on
// generated scenes at 640x480 with refraction (BM_Povray*, slow: not for CI; run them with
// --benchmark_filter=Povray).
#include "corpus/analytic_surfaces.hpp"
#include "common/atomic_file.hpp"
#include "analyzer/obj_writer.hpp"
#include "scene/config.hpp"
#include "scene/mesh2_writer.hpp"
#include "pipeline/generate_scene.hpp"
#include "scene/frame_include.hpp"
#include "scene/scene_writer.hpp"
#include "scene/simplify.hpp"

#include <benchmark/benchmark.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <chrono>
#include <cmath>

#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <unistd.h>

namespace {

namespace fs = std::filesystem;
using namespace toonwater;

// n×n height field z = A sin(kx) cos(ky): n = 235 gives 55,225 vertices, n = 1000 one million.
TriangleMesh wave_field(int n) { return make_wave_field(n, 0.1, 6.0, 1.0).mesh; }

fs::path scratch(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("toonwater-bench-" + std::to_string(::getpid()) + "-" + name);
  fs::create_directories(dir);
  return dir;
}

void BM_PovgenFrame(benchmark::State& state) {
  const TriangleMesh mesh = wave_field(static_cast<int>(state.range(0)));
  const SceneConfig config;
  const LightGeometry light = light_geometry(config.light, Axis::z);
  const fs::path dir = scratch("frame");
  double analysis = 0, writing = 0;
  for (auto _ : state) {
    const auto s = prepare_surface(mesh, Axis::z, &config.flow, nullptr);
    const auto start = std::chrono::steady_clock::now();
    const CameraPlacement camera = frame_camera(config, Axis::z, s.mesh.min, s.mesh.max);
    const std::string text =
        mesh_include(s, "Water", texture_coordinates(s, light),
                     shell_offsets(config.outline, s.mesh, camera, config.render.width));
    write_file_atomically(dir / "water_0001.inc", text);
    writing += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    analysis += s.analysis_seconds;
  }
  state.counters["vertices"] = static_cast<double>(mesh.positions.size());
  state.counters["analysis_s"] = benchmark::Counter(analysis, benchmark::Counter::kAvgIterations);
  state.counters["writing_s"] = benchmark::Counter(writing, benchmark::Counter::kAvgIterations);
  fs::remove_all(dir);
}
BENCHMARK(BM_PovgenFrame)->Arg(235)->Arg(707)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Mesh2Write(benchmark::State& state) {
  const TriangleMesh mesh = wave_field(static_cast<int>(state.range(0)));
  std::vector<Vec3> normals(mesh.positions.size(), Vec3(0, 0, 1));
  const auto sm = make_scene_mesh(mesh, normals, false, Axis::z);
  const auto uv = toon_coordinates(sm, {}, {});
  const fs::path dir = scratch("mesh2");
  std::size_t bytes = 0;
  for (auto _ : state) {
    std::string text;
    append_mesh2(text, "Water_mesh", sm, uv);
    write_file_atomically(dir / "water.inc", text);
    bytes = text.size();
  }
  state.counters["vertices"] = static_cast<double>(mesh.positions.size());
  state.counters["bytes"] = static_cast<double>(bytes);
  fs::remove_all(dir);
}
BENCHMARK(BM_Mesh2Write)->Arg(1000)->Unit(benchmark::kMillisecond)->UseRealTime();

// POV-Ray's statistics: "Parse Time: ... (0.812 seconds)".
double povray_seconds(const std::string& log, const std::string& what) {
  std::smatch m;
  if (std::regex_search(log, m, std::regex(what + R"( Time:.*\(([0-9.]+) seconds\))")))
    return std::stod(m[1]);
  return -1;
}

void BM_PovrayRender(benchmark::State& state) {
  // A wave field as the water (flow regions, outlines, reflection and refraction on) with a
  // submerged sphere, written by povgen, rendered at 640x480 without antialiasing.
  const int n = static_cast<int>(state.range(0));
  const fs::path dir = scratch("povray" + std::to_string(n));
  const TriangleMesh water = wave_field(n);
  write_obj(dir / "water.obj", water);
  ConfigSources sources;
  sources.overrides = {"render.antialias=false"};
  const SceneConfig config = load_config(sources);
  PovgenRequest request;
  request.water_pattern = (dir / "water.obj").string();
  request.up = Axis::z;
  request.out_dir = dir / "scene";
  generate_scene(config, request, {}, nullptr);

  double parse = 0, trace = 0;
  for (auto _ : state) {
    const std::string command = "cd '" + request.out_dir.string() + "' && povray scene.ini 2>&1";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string log;
    char buffer[4096];
    for (std::size_t k; (k = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;)
      log.append(buffer, k);
    if (::pclose(pipe) != 0) state.SkipWithError("povray failed");
    parse += povray_seconds(log, "Parse");
    trace += povray_seconds(log, "Trace");
  }
  state.counters["vertices"] = static_cast<double>(water.positions.size());
  state.counters["parse_s"] = benchmark::Counter(parse, benchmark::Counter::kAvgIterations);
  state.counters["trace_s"] = benchmark::Counter(trace, benchmark::Counter::kAvgIterations);
  fs::remove_all(dir);
}
// 55,225 and 499,849 vertices.
BENCHMARK(BM_PovrayRender)
    ->Arg(235)
    ->Arg(707)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// The water's render mesh simplified (water.simplify, scene/simplify.hpp) against the full mesh:
// an n×n calm frame (n = 1000: one million vertices) with one ripple packet, the default scene
// at 640×360 without antialiasing. Reports POV-Ray's wall time, parse and trace, the include's
// bytes, the share of pixels differing by more than 16/255, and the simplification's time.
TriangleMesh calm_with_ripple(int n) {
  TriangleMesh m;
  m.positions.reserve(static_cast<std::size_t>(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double x = -1 + 2.0 * i / (n - 1), y = -1 + 2.0 * j / (n - 1);
      const double r2 = (x - 0.3) * (x - 0.3) + (y + 0.2) * (y + 0.2);
      const double envelope = r2 < 0.25 ? std::exp(-r2 / 0.02) : 0.0;  // 0 beyond r = 0.5
      m.positions.emplace_back(x, y, 0.02 * envelope * std::cos(60.0 * std::sqrt(r2)));
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({b, d, c});
    }
  return m;
}

// The simplification alone on the same frame (the default scene's camera and flow settings at
// 640×360, water.simplify = 0.5): its time and the faces it keeps.
void BM_SimplifyWater(benchmark::State& state) {
  const TriangleMesh water = calm_with_ripple(static_cast<int>(state.range(0)));
  ConfigSources sources;
  sources.overrides = {"render.width=640", "render.height=360", "water.simplify=0.5"};
  const SceneConfig config = load_config(sources);
  const LightGeometry light = light_geometry(config.light, Axis::z);
  const PreparedSurface full = prepare_surface(water, Axis::z, &config.flow, nullptr);
  SceneLayout layout;
  layout.config = &config;
  layout.up = Axis::z;
  layout.water_min = full.mesh.min;
  layout.water_max = full.mesh.max;
  layout.camera = frame_camera(config, Axis::z, full.mesh.min, full.mesh.max);
  std::size_t kept = 0;
  double seconds = 0;
  for (auto _ : state) {
    state.PauseTiming();
    PreparedSurface s = full;
    std::vector<TextureCoordinate> uv = water_coordinates(s, light, layout);
    state.ResumeTiming();
    const auto start = std::chrono::steady_clock::now();
    const SimplifyStats stats = simplify_water(s, uv, layout, &config.flow);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    kept = stats.faces_after;
  }
  state.counters["faces"] = static_cast<double>(full.mesh.triangles.size());
  state.counters["faces_kept"] = static_cast<double>(kept);
  state.counters["simplify_s"] = benchmark::Counter(seconds, benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_SimplifyWater)->Arg(300)->Arg(1000)->Unit(benchmark::kSecond)->UseRealTime();

struct RenderedScene {
  double wall = 0, parse = 0, trace = 0;
  std::vector<unsigned char> pixels;
};

RenderedScene render_scene_dir(const fs::path& dir) {
  RenderedScene r;
  const std::string command = "cd '" + dir.string() + "' && povray scene.ini 2>&1";
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = ::popen(command.c_str(), "r");
  std::string log;
  char buffer[4096];
  for (std::size_t k; (k = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) log.append(buffer, k);
  const int status = ::pclose(pipe);
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (status != 0) return r;
  r.parse = povray_seconds(log, "Parse");
  r.trace = povray_seconds(log, "Trace");
  auto in = OIIO::ImageInput::open((dir / "frame.png").string());
  if (!in) return r;
  const OIIO::ImageSpec& spec = in->spec();
  r.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * 3);
  in->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, r.pixels.data());
  return r;
}

void BM_SimplifiedRender(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const fs::path dir = scratch("simplify" + std::to_string(n));
  const TriangleMesh water = calm_with_ripple(n);
  write_obj(dir / "water.obj", water);
  auto generate = [&](const std::string& simplify) {
    ConfigSources sources;
    sources.overrides = {"render.antialias=false", "render.width=640", "render.height=360",
                         "water.simplify=" + simplify};
    const SceneConfig config = load_config(sources);
    PovgenRequest request;
    request.water_pattern = (dir / "water.obj").string();
    request.up = Axis::z;
    request.out_dir = dir / ("scene_" + simplify);
    return generate_scene(config, request, {}, nullptr);
  };
  const PovgenReport full_report = generate("0");
  const PovgenReport report = generate("0.5");

  RenderedScene full, simplified;
  for (auto _ : state) {
    full = render_scene_dir(dir / "scene_0");
    simplified = render_scene_dir(dir / "scene_0.5");
  }
  if (full.pixels.empty() || full.pixels.size() != simplified.pixels.size()) {
    state.SkipWithError("povray failed");
    fs::remove_all(dir);
    return;
  }
  std::size_t differing = 0;
  for (std::size_t p = 0; p < full.pixels.size(); p += 3) {
    bool differs = false;
    for (std::size_t c = 0; c < 3; ++c)
      differs |= std::abs(int(full.pixels[p + c]) - int(simplified.pixels[p + c])) > 16;
    differing += differs;
  }
  const double bytes_full = static_cast<double>(fs::file_size(dir / "scene_0" / "water_0000.inc"));
  const double bytes = static_cast<double>(fs::file_size(dir / "scene_0.5" / "water_0000.inc"));
  state.counters["vertices"] = static_cast<double>(water.positions.size());
  state.counters["faces_kept"] = static_cast<double>(report.faces_kept);
  state.counters["faces"] = static_cast<double>(full_report.faces);
  state.counters["wall_full_s"] = full.wall;
  state.counters["wall_s"] = simplified.wall;
  state.counters["wall_ratio"] = simplified.wall / full.wall;
  state.counters["parse_full_s"] = full.parse;
  state.counters["parse_s"] = simplified.parse;
  state.counters["trace_full_s"] = full.trace;
  state.counters["trace_s"] = simplified.trace;
  state.counters["bytes_ratio"] = bytes / bytes_full;
  state.counters["differing_pct"] =
      100.0 * static_cast<double>(differing) / static_cast<double>(full.pixels.size() / 3);
  state.counters["simplify_s"] = report.simplify_seconds;
  state.counters["simplify_per_parse_saved"] =
      report.simplify_seconds / std::max(full.parse - simplified.parse, 1e-9);
  fs::remove_all(dir);
}
BENCHMARK(BM_SimplifiedRender)
    ->Arg(300)
    ->Arg(1000)
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);

// Outline shells culled by the camera (scene/shell_culling.hpp) on an n×n wave frame (n = 707:
// 499,849 vertices), opaque water (where the rule culls), 320×180 without antialiasing: POV-Ray's
// parse time without outlines, with culled shells and with every shell face, rendered in turn,
// five rounds, medians. parse_ratio (culled / no outlines) is the figure with a target (<= 1.3);
// parse_ratio_unculled is what refracting water, where nothing is culled, pays.
void BM_PovrayShellCulling(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const fs::path dir = scratch("culling" + std::to_string(n));
  const TriangleMesh water = wave_field(n);
  {
    std::string obj;
    char line[96];
    for (const Vec3& p : water.positions) {
      std::snprintf(line, sizeof line, "v %.9g %.9g %.9g\n", p.x(), p.y(), p.z());
      obj += line;
    }
    for (const Triangle& t : water.triangles) {
      std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1);
      obj += line;
    }
    write_file_atomically(dir / "water.obj", obj);
  }
  PovgenReport culled_report;
  auto generate = [&](const std::string& name, bool outline, bool cull) {
    ConfigSources sources;
    sources.overrides = {"render.antialias=false", "render.width=320", "render.height=180",
                         "water.transmit=0",
                         std::string("outline.enabled=") + (outline ? "true" : "false")};
    PovgenRequest request;
    request.water_pattern = (dir / "water.obj").string();
    request.up = Axis::z;
    request.out_dir = dir / name;
    request.cull_shells = cull;
    const PovgenReport r = generate_scene(load_config(sources), request, {}, nullptr);
    if (outline && cull) culled_report = r;
  };
  generate("plain", false, true);
  generate("culled", true, true);
  generate("unculled", true, false);
  // Nine rounds of the two scenes the target compares, in turn (which goes first alternates),
  // the ratio taken round by round so that the machine's drift cancels; every face's scene,
  // much slower, in three of them (its pixels against the culled scene's each time).
  std::vector<double> plain, culled, unculled, ratios;
  bool identical = true;
  for (auto _ : state) {
    for (int round = 0; round < 9; ++round) {
      RenderedScene a, b;
      if (round % 2 == 0) {
        a = render_scene_dir(dir / "plain");
        b = render_scene_dir(dir / "culled");
      } else {
        b = render_scene_dir(dir / "culled");
        a = render_scene_dir(dir / "plain");
      }
      plain.push_back(a.parse), culled.push_back(b.parse);
      ratios.push_back(b.parse / a.parse);
      if (round % 4 == 0) {
        const RenderedScene c = render_scene_dir(dir / "unculled");
        if (b.pixels.empty() || b.pixels != c.pixels) identical = false;
        unculled.push_back(c.parse);
      }
    }
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  if (!identical) state.SkipWithError("culled and unculled shells rendered different pixels");
  state.counters["vertices"] = static_cast<double>(water.positions.size());
  state.counters["shell_faces_kept_pct"] =
      100.0 * static_cast<double>(culled_report.shell_faces_kept) /
      static_cast<double>(std::max<std::size_t>(culled_report.shell_faces, 1));
  state.counters["parse_plain_s"] = median(plain);
  state.counters["parse_culled_s"] = median(culled);
  state.counters["parse_unculled_s"] = median(unculled);
  state.counters["parse_ratio"] = median(ratios);
  state.counters["parse_ratio_min"] = *std::min_element(ratios.begin(), ratios.end());
  state.counters["parse_ratio_max"] = *std::max_element(ratios.begin(), ratios.end());
  state.counters["parse_ratio_unculled"] = median(unculled) / median(plain);
  fs::remove_all(dir);
}
BENCHMARK(BM_PovrayShellCulling)->Arg(707)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
