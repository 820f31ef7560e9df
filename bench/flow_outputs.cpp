// flow_outputs: writes what the flow stage computes, so that a faster flow stage can be checked
// against the build before it, and compares two such dumps.
//
//   flow_outputs write DIR      one file a case in DIR
//   flow_outputs compare A B    exit status 0 when B matches A: every count, label, free-surface
//                               flag, rest height, region of interest, threshold and flicker
//                               equal, the flow fields within 1e-12 relative
//
// The cases: bench_analyzer's wave fields (235² and 1000² vertices) labelled alone and as the
// second frame of a coherent sequence (FlowWithCoherence), and, where ../shared/data is
// present, every frame of mantaflow-wake and blender-ocean analysed alone and in sequence with
// coherence (as povgen does). The program uses only the analyzer's public interface, so the
// same source builds against an older library.
#include "analyzer/analysis.hpp"
#include "analyzer/flow_coherence.hpp"
#include "analyzer/mesh_reader.hpp"
#include "corpus/analytic_surfaces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace toonwater {
namespace {

namespace fs = std::filesystem;

// One case's outputs as text: summary lines "name value", then one line a vertex:
// "free_surface label field smoothed_field". Doubles with 17 significant digits (exact).
std::string dump(const FlowRegions& flow, double flicker) {
  std::ostringstream out;
  out.precision(17);
  out << "criterion " << static_cast<int>(flow.criterion) << '\n'
      << "threshold " << flow.threshold << '\n'
      << "scale_length " << flow.scale_length << '\n'
      << "min_region_area " << flow.min_region_area << '\n'
      << "median_edge_length " << flow.median_edge_length << '\n'
      << "rest_height " << flow.rest_height << '\n'
      << "roi " << flow.region_of_interest.min.transpose() << ' '
      << flow.region_of_interest.max.transpose() << '\n'
      << "free_surface_vertices " << flow.free_surface_vertices << '\n'
      << "free_surface_patches_dropped " << flow.free_surface_patches_dropped << '\n'
      << "ridge_vertices " << flow.ridge_vertices << '\n'
      << "valley_vertices " << flow.valley_vertices << '\n'
      << "regions " << flow.regions << '\n'
      << "specks_faded " << flow.specks_faded << '\n'
      << "flicker " << flicker << '\n'
      << "vertices " << flow.label.size() << '\n';
  for (std::size_t v = 0; v < flow.label.size(); ++v)
    out << int(flow.free_surface.empty() ? 0 : flow.free_surface[v]) << ' ' << int(flow.label[v])
        << ' ' << flow.field[v] << ' '
        << (flow.smoothed_field.empty() ? 0.0 : flow.smoothed_field[v]) << '\n';
  return out.str();
}

void write_file(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
  std::cout << path.string() << '\n';
}

void write_wave_cases(const fs::path& dir) {
  for (const int n : {235, 1000}) {
    const TriangleMesh mesh = make_wave_field(n, 0.1, 6.0, 1.0).mesh;
    const MeshTopology topology = analyze_topology(mesh);
    const CurvatureField curvature = compute_curvature(mesh, topology);
    FlowOptions options;
    options.up = Axis::z;
    const std::string name = "wave-" + std::to_string(n);
    write_file(dir / (name + "-alone.txt"),
               dump(find_flow_regions(mesh, topology, curvature, options), 0.0));
    FlowCoherence coherence;
    find_flow_regions(mesh, topology, curvature, options, &coherence);
    const FlowRegions second = find_flow_regions(mesh, topology, curvature, options, &coherence);
    write_file(dir / (name + "-coherent.txt"), dump(second, coherence.last_flicker()));
  }
}

void write_sequence_cases(const fs::path& dir, const fs::path& data, const std::string& sequence,
                          int frames) {
  FlowCoherence coherence;
  for (int frame = 1; frame <= frames; ++frame) {
    char file[64];
    std::snprintf(file, sizeof file, "water_%04d.obj", frame);
    const fs::path path = data / sequence / file;
    if (!fs::exists(path)) {
      std::cerr << "skipped (absent): " << path.string() << '\n';
      return;
    }
    const TriangleMesh mesh = read_mesh(path).mesh;
    AnalyzeOptions options;
    options.flow.up = Axis::z;
    const std::string name = sequence + "-" + std::to_string(frame);
    write_file(dir / (name + "-alone.txt"), dump(analyze_mesh(mesh, options).flow, 0.0));
    options.coherence = &coherence;
    const Analysis coherent = analyze_mesh(mesh, options);
    write_file(dir / (name + "-coherent.txt"), dump(coherent.flow, coherence.last_flicker()));
  }
}

std::vector<std::string> lines_of(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// Compares one case; returns the number of mismatches and raises the largest relative field
// difference seen.
std::size_t compare_case(const fs::path& a, const fs::path& b, double& largest_difference) {
  const std::vector<std::string> expected = lines_of(a), actual = lines_of(b);
  if (expected.size() != actual.size()) {
    std::cout << b.string() << ": " << actual.size() << " lines, expected " << expected.size()
              << '\n';
    return 1;
  }
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] == actual[i]) continue;
    std::istringstream e(expected[i]), o(actual[i]);
    int e_surface = 0, e_label = 0, o_surface = 0, o_label = 0;
    double e_field[2] = {}, o_field[2] = {};
    const bool vertex_line =
        static_cast<bool>(e >> e_surface >> e_label >> e_field[0] >> e_field[1]) &&
        static_cast<bool>(o >> o_surface >> o_label >> o_field[0] >> o_field[1]);
    bool same = vertex_line && e_surface == o_surface && e_label == o_label;
    for (int k = 0; k < 2 && same; ++k) {
      const double scale = std::max({std::abs(e_field[k]), std::abs(o_field[k]), 1e-300});
      const double difference = std::abs(e_field[k] - o_field[k]) / scale;
      largest_difference = std::max(largest_difference, difference);
      same = difference <= 1e-12;
    }
    if (!same && ++mismatches <= 5)
      std::cout << b.filename().string() << " line " << i + 1 << ": expected \"" << expected[i]
                << "\", got \"" << actual[i] << "\"\n";
  }
  return mismatches;
}

int compare(const fs::path& a, const fs::path& b) {
  std::size_t cases = 0, failed = 0;
  double largest_difference = 0.0;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(a)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& file : files) {
    ++cases;
    const fs::path other = b / file.filename();
    if (!fs::exists(other)) {
      std::cout << other.string() << ": missing\n";
      ++failed;
      continue;
    }
    failed += compare_case(file, other, largest_difference) > 0;
  }
  std::cout << cases << " cases, " << failed << " differ; largest relative field difference "
            << largest_difference << '\n';
  return failed == 0 && cases > 0 ? 0 : 1;
}

}  // namespace
}  // namespace toonwater

int main(int argc, char** argv) {
  using namespace toonwater;
  const std::string mode = argc > 1 ? argv[1] : "";
  if (mode == "write" && argc == 3) {
    const fs::path dir = argv[2];
    fs::create_directories(dir);
    write_wave_cases(dir);
    const fs::path data = fs::path(TOONWATER_SHARED_DIR) / "data";
    write_sequence_cases(dir, data, "mantaflow-wake", 30);
    write_sequence_cases(dir, data, "blender-ocean", 4);
    return 0;
  }
  if (mode == "compare" && argc == 4) return compare(argv[2], argv[3]);
  std::cerr << "usage: flow_outputs write DIR | flow_outputs compare A B\n";
  return 2;
}
