// The report: runs the study and the pipeline timings, writes CSV, SVG and Markdown; see
// report.hpp. The conclusions ("when each estimator is the better choice") are computed from the
// samples of this run, not written in advance.
#include "report/report.hpp"

#include "analyzer/analytic_surfaces.hpp"
#include "analyzer/atomic_file.hpp"
#include "report/svg_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <thread>

namespace toonwater::report {
namespace {

namespace fs = std::filesystem;

std::string format(const char* spec, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, spec, value);
  return buffer;
}

std::string g(double value) { return format("%.3g", value); }

// ---- inputs ----

std::vector<std::size_t> study_targets(ReportSize size) {
  switch (size) {
    case ReportSize::quick: return {1000, 4000, 16000};
    case ReportSize::standard: return {1000, 4000, 16000, 64000, 250000};
    case ReportSize::full: return {1000, 4000, 16000, 64000, 250000, 1000000};
  }
  return {};
}

// The paper's frame had 55,091 vertices; 235² = 55,225.
fs::path write_height_field(const fs::path& dir, int side) {
  const TriangleMesh m = make_wave_field(side, 0.1, 6.0, 1.0).mesh;
  std::string text;
  char line[96];
  for (const Vec3& p : m.positions) {
    // Height field in the xz plane, y up, as toonwater's default axis.
    std::snprintf(line, sizeof line, "v %.17g %.17g %.17g\n", p.x(), p.z(), p.y());
    text += line;
  }
  for (const Triangle& t : m.triangles) {
    std::snprintf(line, sizeof line, "f %d %d %d\n", t[0] + 1, t[2] + 1, t[1] + 1);
    text += line;
  }
  const fs::path path = dir / ("height_field_" + std::to_string(side * side) + ".obj");
  write_file_atomically(path, text);
  return path;
}

std::vector<PipelineInput> pipeline_inputs(const ReportOptions& options, const fs::path& work) {
  std::vector<PipelineInput> inputs;
  const int side = options.size == ReportSize::quick ? 101 : 235;
  inputs.push_back({"generated height field", write_height_field(work, side), Axis::y});
  if (options.size == ReportSize::full)
    inputs.push_back({"generated height field", write_height_field(work, 708), Axis::y});
  const fs::path wake = options.data_dir / "mantaflow-wake" / "water_0030.obj";
  const fs::path ocean = options.data_dir / "blender-ocean" / "water_0001.obj";
  if (fs::exists(wake)) inputs.push_back({"mantaflow-wake frame 30", wake, Axis::z});
  if (fs::exists(ocean) && options.size != ReportSize::quick)
    inputs.push_back({"blender-ocean frame 1", ocean, Axis::z});
  return inputs;
}

// ---- lookups over the samples ----

const StudySample* find(const std::vector<StudySample>& samples, const std::string& surface,
                        const std::string& sampling, const std::string& method,
                        std::size_t vertices) {
  for (const StudySample& s : samples)
    if (s.surface == surface && s.sampling == sampling && s.method == method && s.vertices == vertices)
      return &s;
  return nullptr;
}

std::vector<std::size_t> resolutions(const std::vector<StudySample>& samples,
                                     const std::string& surface) {
  std::vector<std::size_t> v;
  for (const StudySample& s : samples)
    if (s.surface == surface && std::find(v.begin(), v.end(), s.vertices) == v.end())
      v.push_back(s.vertices);
  std::sort(v.begin(), v.end());
  return v;
}

// Observed order of convergence in the mesh spacing h ∝ N^(-1/2), from the coarsest to the
// finest resolution: error ∝ h^p.
double order(const StudySample& coarse, const StudySample& fine, bool mean) {
  const double e0 = mean ? coarse.rms_mean : coarse.rms_gaussian;
  const double e1 = mean ? fine.rms_mean : fine.rms_gaussian;
  return std::log(e0 / e1) / (0.5 * std::log(double(fine.vertices) / double(coarse.vertices)));
}

// ---- outputs ----

std::string study_csv(const std::vector<StudySample>& samples) {
  std::string csv = "surface,sampling,method,vertices,rms_K,max_K,rms_H,max_H,median_seconds\n";
  for (const StudySample& s : samples)
    csv += s.surface + "," + s.sampling + "," + s.method + "," + std::to_string(s.vertices) + "," +
           format("%.9g", s.rms_gaussian) + "," + format("%.9g", s.max_gaussian) + "," +
           format("%.9g", s.rms_mean) + "," + format("%.9g", s.max_mean) + "," +
           format("%.9g", s.seconds) + "\n";
  return csv;
}

std::string pipeline_csv(const std::vector<PipelineTiming>& rows) {
  std::string csv = "input,vertices,analysis_one_ring_s,analysis_jet_s,scene_writing_s,povray_s,total_s\n";
  for (const PipelineTiming& t : rows) {
    const std::string povray = t.povray ? format("%.6g", *t.povray) : "";
    const std::string total =
        t.povray ? format("%.6g", t.analysis_one_ring + t.scene_writing + *t.povray) : "";
    csv += t.name + "," + std::to_string(t.vertices) + "," + format("%.6g", t.analysis_one_ring) +
           "," + format("%.6g", t.analysis_jet) + "," + format("%.6g", t.scene_writing) + "," +
           povray + "," + total + "\n";
  }
  return csv;
}

const std::map<std::string, std::string> method_colors = {
    {"one-ring", "#d62728"}, {"one-ring+smooth2", "#ff9896"}, {"jet", "#1f77b4"},
    {"jet+smooth2", "#9edae5"}};
const std::map<std::string, std::string> surface_dashes = {
    {"sphere", ""}, {"uv sphere", "4,2,1,2"}, {"torus", "6,3"}, {"ellipsoid", "2,2"},
    {"saddle", "8,3,2,3"}, {"height field", "1,4"}};

std::string error_plot(const std::vector<StudySample>& samples, const std::string& sampling,
                       bool mean) {
  LogLogPlot plot;
  plot.title = std::string(mean ? "H" : "K") + " error against run time, " + sampling + " meshes";
  plot.x_label = "median run time of the curvature stage (s)";
  plot.y_label = std::string("RMS error of ") + (mean ? "H" : "K") + " / RMS of the exact value";
  for (const Method& method : study_methods()) {
    for (const std::string& surface : study_surfaces) {
      PlotSeries series{method.name + ", " + surface, method_colors.at(method.name),
                        surface_dashes.at(surface), {}};
      for (std::size_t n : resolutions(samples, surface))
        if (const StudySample* s = find(samples, surface, sampling, method.name, n))
          series.points.emplace_back(s->seconds, mean ? s->rms_mean : s->rms_gaussian);
      plot.series.push_back(std::move(series));
    }
  }
  return render_svg(plot);
}

// ---- the Markdown ----

std::string largest_resolution_table(const std::vector<StudySample>& samples,
                                     const std::string& sampling) {
  std::string md =
      "| surface | method | vertices | RMS K | max K | RMS H | max H | time (ms) |\n"
      "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (const std::string& surface : study_surfaces) {
    const std::size_t n = resolutions(samples, surface).back();
    for (const Method& method : study_methods()) {
      const StudySample* s = find(samples, surface, sampling, method.name, n);
      if (!s) continue;
      md += "| " + surface + " | " + method.name + " | " + std::to_string(n) + " | " +
            g(s->rms_gaussian) + " | " + g(s->max_gaussian) + " | " + g(s->rms_mean) + " | " +
            g(s->max_mean) + " | " + format("%.2f", 1e3 * s->seconds) + " |\n";
    }
  }
  return md;
}

std::string order_table(const std::vector<StudySample>& samples, const std::string& sampling) {
  std::string md = "| surface |";
  std::string rule = "|---|";
  for (const Method& m : study_methods()) {
    md += " " + m.name + " K | " + m.name + " H |";
    rule += "---:|---:|";
  }
  md += "\n" + rule + "\n";
  for (const std::string& surface : study_surfaces) {
    const auto n = resolutions(samples, surface);
    md += "| " + surface + " |";
    for (const Method& m : study_methods()) {
      const StudySample* coarse = find(samples, surface, sampling, m.name, n.front());
      const StudySample* fine = find(samples, surface, sampling, m.name, n.back());
      if (!coarse || !fine) {
        md += " | |";
        continue;
      }
      md += ' ';
      md += format("%.2f", order(*coarse, *fine, false));
      md += " | ";
      md += format("%.2f", order(*coarse, *fine, true));
      md += " |";
    }
    md += "\n";
  }
  return md;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) { lo = std::min(lo, v); hi = std::max(hi, v); }
  bool empty() const { return lo > hi; }
  std::string text() const { return empty() ? "n/a" : g(lo) + " to " + g(hi); }
};

// Ratios a/b of the RMS errors of two methods over every surface, at resolutions ≥ min_vertices.
Range error_ratio(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& a, const std::string& b, bool mean, std::size_t min_vertices) {
  Range r;
  for (const std::string& surface : study_surfaces)
    for (std::size_t n : resolutions(samples, surface)) {
      if (n < min_vertices) continue;
      const StudySample* x = find(samples, surface, sampling, a, n);
      const StudySample* y = find(samples, surface, sampling, b, n);
      if (x && y) r.add(mean ? x->rms_mean / y->rms_mean : x->rms_gaussian / y->rms_gaussian);
    }
  return r;
}

// Orders of convergence of one method over every surface.
Range order_range(const std::vector<StudySample>& samples, const std::string& sampling,
                  const std::string& method, bool mean) {
  Range r;
  for (const std::string& surface : study_surfaces) {
    const auto n = resolutions(samples, surface);
    const StudySample* coarse = find(samples, surface, sampling, method, n.front());
    const StudySample* fine = find(samples, surface, sampling, method, n.back());
    if (coarse && fine && n.size() > 1) r.add(order(*coarse, *fine, mean));
  }
  return r;
}

// The method with the lowest RMS error in H (then K) at the finest resolution, per surface.
std::map<std::string, int> winners(const std::vector<StudySample>& samples, const std::string& sampling) {
  std::map<std::string, int> wins;
  for (const std::string& surface : study_surfaces) {
    const std::size_t n = resolutions(samples, surface).back();
    const StudySample* best = nullptr;
    for (const Method& m : study_methods())
      if (const StudySample* s = find(samples, surface, sampling, m.name, n))
        if (!best || s->rms_mean + s->rms_gaussian < best->rms_mean + best->rms_gaussian) best = s;
    if (best) ++wins[best->method];
  }
  return wins;
}

std::string wins_text(const std::map<std::string, int>& wins) {
  std::string text;
  for (const auto& [method, count] : wins)
    text += (text.empty() ? "" : ", ") + method + " on " + std::to_string(count);
  return text + " of " + std::to_string(study_surfaces.size()) + " surfaces";
}

std::string conclusions(const std::vector<StudySample>& samples) {
  const std::size_t ten_k = 10000;
  const Range regular_h = error_ratio(samples, "regular", "jet", "one-ring", true, 0);
  const Range jitter_h = error_ratio(samples, "jittered", "one-ring", "jet", true, ten_k);
  const Range jitter_k = error_ratio(samples, "jittered", "one-ring", "jet", false, ten_k);
  const Range smooth_h = error_ratio(samples, "jittered", "one-ring", "one-ring+smooth2", true, ten_k);
  Range cost;
  for (const std::string& surface : study_surfaces) {
    const std::size_t n = resolutions(samples, surface).back();
    for (const std::string& sampling : study_samplings) {
      const StudySample* jet = find(samples, surface, sampling, "jet", n);
      const StudySample* one = find(samples, surface, sampling, "one-ring", n);
      if (jet && one && one->seconds > 0) cost.add(jet->seconds / one->seconds);
    }
  }
  const bool requirement = !jitter_h.empty() && jitter_h.lo >= 5.0 && jitter_k.lo > 1.0;

  std::string md;
  md += "- **Regular triangulations** (simulation grids, subdivided surfaces): orders of "
        "convergence in H: one-ring " + order_range(samples, "regular", "one-ring", true).text() +
        ", jet " + order_range(samples, "regular", "jet", true).text() + "; the jet's H error is " +
        regular_h.text() + "× the one-ring's; best per surface at the finest resolution: " +
        wins_text(winners(samples, "regular")) + ". The one-ring operators take " + cost.text() +
        "× less time than the jet.\n";
  md += "- **Irregular triangulations** (jittered; remeshed or simplified surfaces): orders in H: "
        "one-ring " + order_range(samples, "jittered", "one-ring", true).text() +
        " (near 0: the cotangent H does not converge), jet " +
        order_range(samples, "jittered", "jet", true).text() + ". From 10k vertices up the jet "
        "is " + jitter_h.text() + "× more accurate in H and " + jitter_k.text() +
        "× in K (requirement: at least 5× in H and more accurate in K: " +
        (requirement ? "met" : "NOT met") + "); best: " + wins_text(winners(samples, "jittered")) +
        ". Two smoothing steps make the one-ring H " + smooth_h.text() +
        "× more accurate there at little cost, and order " +
        order_range(samples, "jittered", "one-ring+smooth2", true).text() + ".\n";
  md += "- **Noisy positions**: orders in H: one-ring " +
        order_range(samples, "noisy", "one-ring", true).text() + ", jet " +
        order_range(samples, "noisy", "jet", true).text() + ", jet+smooth2 " +
        order_range(samples, "noisy", "jet+smooth2", true).text() +
        " (negative: the error grows as the spacing shrinks, since noise of a fixed share of "
        "the edge length has second differences ∝ 1/h); best: " +
        wins_text(winners(samples, "noisy")) +
        ". Larger neighbourhoods — the jet's two-ring, smoothing — average the noise out.\n";
  return md;
}

std::string pipeline_table(const std::vector<PipelineTiming>& rows, int width, int height) {
  std::string md =
      "| input | vertices | flow analysis, one-ring (s) | flow analysis, jet (s) | scene writing "
      "(s) | POV-Ray parse + trace (s) | total (s) |\n|---|---:|---:|---:|---:|---:|---:|\n";
  for (const PipelineTiming& t : rows) {
    md += "| " + t.name + " | " + std::to_string(t.vertices) + " | " +
          format("%.3f", t.analysis_one_ring) + " | " + format("%.3f", t.analysis_jet) + " | " +
          format("%.3f", t.scene_writing) + " | " +
          (t.povray ? format("%.2f", *t.povray) : "not measured (" + t.povray_failure + ")") +
          " | " + (t.povray ? format("%.2f", t.analysis_one_ring + t.scene_writing + *t.povray) : "") +
          " |\n";
  }
  md += "| paper (You et al., W.F.S.) | 55091 | 1325 | | | | |\n\n";
  md += "POV-Ray renders one frame at " + std::to_string(width) + "×" + std::to_string(height) +
        " with povgen's default scene (flow regions and outlines on, refraction and reflection "
        "of the water's default finish), one process. The paper's figure is its Water Flow "
        "Shader's analysis time for one 55,091-vertex frame.\n";
  return md;
}

std::string ripple_csv(const std::vector<RippleRow>& rows) {
  std::string s = "criterion,n,jittered,crest_ridge,trough_valley,calm_labelled,labelled_share\n";
  for (const RippleRow& r : rows)
    s += r.criterion + "," + std::to_string(r.n) + "," + (r.jittered ? "1" : "0") + "," +
         g(r.coverage.crest_ridge) + "," + g(r.coverage.trough_valley) + "," +
         g(r.coverage.calm_labelled) + "," + g(r.coverage.labelled_share) + "\n";
  return s;
}

std::string percent(double share) { return format("%.1f %%", 100.0 * share); }

std::string flow_section(const ReportResult& r, double pixels_per_cell) {
  std::string s =
      "The flow regions' criterion (`--criterion`, `flow.criterion`): `mean` (default), s = H/T "
      "with T = 2/L; `paper`, s = sign(H)|K|/T with T = 30/L² (L = sqrt of the free surface's "
      "area; analyzer/flow_regions.hpp).\n\n"
      "**Analytic concentric ripples** (z = a cos kr, a = 0.01, λ = 0.3 on a 2 × 2 sheet, calm "
      "beyond 2.8 λ; jittered: x, y moved by up to 0.3 grid steps). Shares of the vertices near "
      "the crest circles labelled ridge and near the trough circles labelled valley, of calm "
      "water labelled, and of the sheet's area labelled:\n\n"
      "| criterion | mesh | n × n | crests ridge | troughs valley | calm labelled | area labelled |\n"
      "|---|---|---:|---:|---:|---:|---:|\n";
  for (const RippleRow& row : r.ripples)
    s += "| " + row.criterion + " | " + (row.jittered ? "jittered" : "regular") + " | " +
         std::to_string(row.n) + " | " + percent(row.coverage.crest_ridge) + " | " +
         percent(row.coverage.trough_valley) + " | " + percent(row.coverage.calm_labelled) +
         " | " + percent(row.coverage.labelled_share) + " |\n";
  s += "\n**mantaflow-wake from straight above**, " + format("%.0f", pixels_per_cell) +
       " pixels a cell, ridge red and valley green, coherence on, every frame rendered by "
       "POV-Ray and measured on its pixels: frames with regions, share of the flow pixels in "
       "pieces under 4 cells² (specks), and boundary length over its one-cell-smoothed length "
       "(median over the frames; 1 is smooth, a staircase along mesh edges is longer):\n\n";
  if (r.flow_sequence.empty()) return s + "Not measured: " + r.flow_sequence_failure + "\n\n";
  s += "| criterion | frames with regions | specks | boundary roughness | middle frame |\n"
       "|---|---:|---:|---:|---|\n";
  for (const SequenceFlowStudy& f : r.flow_sequence)
    s += "| " + f.criterion + " | " + std::to_string(f.frames_with_regions) + " / " +
         std::to_string(f.frames) + " | " + percent(f.speck_share) + " | " +
         format("%.3f", f.boundary_ratio) + " | ![" + f.criterion + "](" +
         f.picture.filename().string() + ") |\n";
  return s + "\n";
}

std::string render_quality_csv(const RenderQualityResult& r) {
  std::string csv = "preset,width,height,seconds,rmse,band_mismatch\n";
  for (const RenderQualitySample& p : r.presets)
    csv += p.preset + "," + std::to_string(p.width) + "," + std::to_string(p.height) + "," +
           format("%.6g", p.seconds) + "," + format("%.6g", p.rmse) + "," +
           format("%.6g", p.band_mismatch) + "\n";
  return csv;
}

std::string render_quality_plot(const RenderQualityResult& r) {
  LogLogPlot plot{"Rendering error against POV-Ray time", "POV-Ray parse + trace (s)",
                  "error against the reference render", {}};
  PlotSeries rmse{"RMSE (RGB in [0, 1])", "#1f77b4", "", {}};
  PlotSeries bands{"share of pixels in another band", "#d62728", "6,3", {}};
  for (const RenderQualitySample& p : r.presets) {
    rmse.points.emplace_back(p.seconds, p.rmse);
    bands.points.emplace_back(p.seconds, p.band_mismatch);
  }
  plot.series = {rmse, bands};
  return render_svg(plot);
}

std::string render_quality_section(const RenderQualityResult& r, const std::string& scene,
                                   int width, int height) {
  std::string md =
      "Scene: povgen's default scene of the " + scene + " at " + std::to_string(width) + "×" +
      std::to_string(height) + ". Presets (POV-Ray options after scene.ini): draft = half size, "
      "no antialiasing; preview = full size, no antialiasing; final = full size, antialiasing "
      "threshold 0.05, depth 3. Reference: full size, every pixel supersampled (threshold 0, "
      "depth 4), " + format("%.2f", r.reference_seconds) + " s. A smaller image is compared "
      "after pixel replication. Bands: the nearest of the reference's " +
      std::to_string(r.reference_bands) + " flat colours (those covering at least 1% of it). "
      "max_trace_level is povgen's in every preset.\n\n"
      "| preset | size | POV-Ray (s) | RMSE | pixels in another band |\n|---|---|---:|---:|---:|\n";
  for (const RenderQualitySample& p : r.presets)
    md += "| " + p.preset + " | " + std::to_string(p.width) + "×" + std::to_string(p.height) +
          " | " + format("%.2f", p.seconds) + " | " + format("%.4f", p.rmse) + " | " +
          format("%.2f%%", 100.0 * p.band_mismatch) + " |\n";
  return md + "\n![rendering error](render_error.svg)\n\n";
}

}  // namespace

ReportResult write_report(const ReportOptions& options) {
  auto progress = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  const fs::path work = options.out_dir / "work";
  fs::create_directories(work);
  // Scratch meshes and scenes go, whether the run succeeds or throws.
  struct RemoveOnExit {
    fs::path path;
    ~RemoveOnExit() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } remove_work{work};

  ReportResult result;
  StudyOptions study;
  study.target_vertices = study_targets(options.size);
  study.repeats = options.size == ReportSize::quick ? 1 : 3;
  study.progress = [&](const std::string& line) { progress("curvature study " + line); };
  result.study = run_curvature_study(study);

  const int width = options.size == ReportSize::quick ? 160 : 640;
  const int height = options.size == ReportSize::quick ? 120 : 480;
  const std::vector<PipelineInput> inputs = pipeline_inputs(options, work);
  for (const PipelineInput& input : inputs) {
    progress("pipeline: " + input.name + " (" + input.mesh.filename().string() + ")");
    const fs::path scene = work / ("scene_" + std::to_string(result.pipeline.size()));
    result.pipeline.push_back(time_pipeline(input, scene, width, height));
  }
  progress("render quality: presets and reference render of the " + inputs.front().name);
  try {
    result.render_quality = measure_render_quality(work / "scene_0", width, height);
  } catch (const std::exception& e) {  // POV-Ray missing or failing: the rest still reports
    result.render_quality_failure = e.what();
  }

  progress("flow criteria: analytic ripples");
  result.ripples = run_ripple_study(options.size == ReportSize::quick ? std::vector<int>{81, 161}
                                                                      : std::vector<int>{81, 161, 321});
  const fs::path wake_frames = options.data_dir / "mantaflow-wake" / "water_####.obj";
  const double pixels_per_cell = options.size == ReportSize::quick ? 2.0 : 8.0;
  if (!fs::exists(options.data_dir / "mantaflow-wake" / "water_0001.obj")) {
    result.flow_sequence_failure = "the sample simulation was not found in " + options.data_dir.string();
  } else {
    progress("flow criteria: mantaflow-wake from above");
    try {
      // A quick run measures frames 10–15 (the wake at its busiest) at 2 pixels a cell.
      std::optional<povgen::FrameRange> frames;
      if (options.size == ReportSize::quick) frames = povgen::FrameRange{10, 15};
      result.flow_sequence = run_sequence_flow_study(fs::absolute(wake_frames).string(), Axis::z,
                                                     work, options.out_dir, pixels_per_cell,
                                                     {FlowCriterion::mean, FlowCriterion::paper}, frames);
    } catch (const std::exception& e) {
      result.flow_sequence_failure = e.what();
    }
  }
  write_file_atomically(options.out_dir / "flow_ripples.csv", ripple_csv(result.ripples));
  write_file_atomically(options.out_dir / "curvature_errors.csv", study_csv(result.study));
  write_file_atomically(options.out_dir / "pipeline.csv", pipeline_csv(result.pipeline));
  if (result.render_quality) {
    write_file_atomically(options.out_dir / "render_quality.csv",
                          render_quality_csv(*result.render_quality));
    write_file_atomically(options.out_dir / "render_error.svg",
                          render_quality_plot(*result.render_quality));
  }
  std::string plots;
  for (const std::string& sampling : study_samplings) {
    for (bool mean : {true, false}) {
      const std::string name =
          std::string("error_") + (mean ? "H" : "K") + "_" + sampling + ".svg";
      write_file_atomically(options.out_dir / name, error_plot(result.study, sampling, mean));
      plots += "![" + std::string(mean ? "H" : "K") + ", " + sampling + "](" + name + ")\n";
    }
  }

  const char* size_name = options.size == ReportSize::quick      ? "quick"
                          : options.size == ReportSize::standard ? "standard"
                                                                 : "full";
  std::string md = "# toonwater: accuracy and cost\n\n";
  md += "Measured by `toonwater report` (" + std::string(size_name) + " run, " +
        std::to_string(std::thread::hardware_concurrency()) +
        " hardware threads). Raw numbers: [curvature_errors.csv](curvature_errors.csv), "
        "[pipeline.csv](pipeline.csv), [render_quality.csv](render_quality.csv).\n\n";
  md += "## 1. Curvature error against run time\n\n"
        "Estimators (selected with `toonwater analyze --estimator one-ring|jet --smooth N`):\n"
        "`one-ring` — the paper's angle deficit and cotangent Laplacian (Meyer et al. 2002); "
        "`jet` — cubic height functions fitted over the two-ring (Cazals and Pouget 2005); "
        "`+smooth2` — then two steps of area-weighted smoothing of K and H.\n\n"
        "Surfaces: unit icosphere (sphere), unit UV sphere with 2n × n segments (thin pole fans), "
        "torus R = 1, r = 0.4, ellipsoid 1 × 0.8 × 0.6 "
        "(stretched icosphere), saddle z = (x² − y²)/2, height field z = 0.1 sin 6x cos 6y. "
        "Samplings: regular; jittered (every vertex moved within the surface by up to 0.2 of "
        "the grid step: an irregular triangulation); noisy (moved in a random direction by up "
        "to 2% of the mean edge length, compared with the exact values before the move). "
        "Errors over interior vertices, divided by the RMS of the exact value; time: median of " +
        std::to_string(study.repeats) + " run(s) of the curvature stage.\n\n";
  md += plots + "\n";
  for (const std::string& sampling : study_samplings)
    md += "### " + sampling + " meshes, finest resolution\n\n" +
          largest_resolution_table(result.study, sampling) + "\n";
  md += "### Observed order of convergence (RMS error ∝ h^p, coarsest to finest)\n\n";
  for (const std::string& sampling : study_samplings)
    md += "**" + sampling + "**\n\n" + order_table(result.study, sampling) + "\n";
  md += "## 2. When each estimator is the better choice\n\n" + conclusions(result.study) + "\n";
  md += "## 3. Rendering error against run time\n\n";
  if (!result.render_quality)
    md += "Not measured: " + result.render_quality_failure + "\n\n";
  else
    md += render_quality_section(*result.render_quality,
                                 inputs.front().name + " (" +
                                     std::to_string(result.pipeline.front().vertices) + " vertices)",
                                 width, height);
  md += "## 4. Table 1: time per frame\n\n" + pipeline_table(result.pipeline, width, height);
  md += "\n## 5. Flow regions: the paper's criterion and the default\n\n" +
        flow_section(result, pixels_per_cell);
  if (!fs::exists(options.data_dir / "mantaflow-wake"))
    md += "\nThe sample simulation was not found in " + options.data_dir.string() +
          " (pass `--data DIR`).\n";
  write_file_atomically(options.out_dir / "report.md", md);
  return result;
}

}  // namespace toonwater::report
