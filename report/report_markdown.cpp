#include "report/report_markdown.hpp"

#include "report/number_format.hpp"
#include "report/report_plots.hpp"
#include "report/sample_analysis.hpp"

#include <map>
#include <thread>

namespace toonwater::report {
namespace {

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
  const Range smooth_h =
      error_ratio(samples, "jittered", "one-ring", "one-ring+smooth2", true, ten_k);
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
  md +=
      "- **Regular triangulations** (simulation grids, subdivided surfaces): orders of "
      "convergence in H: one-ring " +
      order_range(samples, "regular", "one-ring", true).text() + ", jet " +
      order_range(samples, "regular", "jet", true).text() + "; the jet's H error is " +
      regular_h.text() + "× the one-ring's; best per surface at the finest resolution: " +
      wins_text(winners(samples, "regular")) + ". The one-ring operators take " + cost.text() +
      "× less time than the jet.\n";
  md +=
      "- **Irregular triangulations** (jittered; remeshed or simplified surfaces): orders in H: "
      "one-ring " +
      order_range(samples, "jittered", "one-ring", true).text() +
      " (near 0: the cotangent H does not converge), jet " +
      order_range(samples, "jittered", "jet", true).text() +
      ". From 10k vertices up the jet "
      "is " +
      jitter_h.text() + "× more accurate in H and " + jitter_k.text() +
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
          " | " +
          (t.povray ? format("%.2f", t.analysis_one_ring + t.scene_writing + *t.povray) : "") +
          " |\n";
  }
  md += "| paper (You et al., W.F.S.) | 55091 | 1325 | | | | |\n\n";
  md += "POV-Ray renders one frame at " + std::to_string(width) + "×" + std::to_string(height) +
        " with povgen's default scene (flow regions and outlines on, refraction and reflection "
        "of the water's default finish), one process. The paper's figure is its Water Flow "
        "Shader's analysis time for one 55,091-vertex frame.\n";
  return md;
}

std::string flow_section(const ReportResult& r, double pixels_per_cell) {
  std::string s =
      "The flow regions' criterion (`--criterion`, `flow.criterion`): `mean` (default), s = H/T "
      "with T = 2/L; `paper`, s = sign(H)|K|/T with T = 30/L² (L = sqrt of the free surface's "
      "area; analyzer/flow_regions.hpp).\n\n"
      "**Analytic concentric ripples** (z = a cos kr, a = 0.01, λ = 0.3 on a 2 × 2 sheet, calm "
      "beyond 2.8 λ; jittered: x, y moved by up to 0.3 grid steps). Shares of the vertices near "
      "the crest circles labelled ridge and near the trough circles labelled valley, of calm "
      "water labelled, and of the sheet's area labelled:\n\n"
      "| criterion | mesh | n × n | crests ridge | troughs valley | calm labelled | area labelled "
      "|\n"
      "|---|---|---:|---:|---:|---:|---:|\n";
  for (const RippleRow& row : r.ripples)
    s += "| " + row.criterion + " | " + (row.jittered ? "jittered" : "regular") + " | " +
         std::to_string(row.n) + " | " + percent(row.coverage.crest_ridge) + " | " +
         percent(row.coverage.trough_valley) + " | " + percent(row.coverage.calm_labelled) + " | " +
         percent(row.coverage.labelled_share) + " |\n";
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

std::string render_quality_section(const RenderQualityResult& r, const std::string& scene,
                                   int width, int height) {
  std::string md =
      "Scene: povgen's default scene of the " + scene + " at " + std::to_string(width) + "×" +
      std::to_string(height) +
      ". Presets (POV-Ray options after scene.ini): draft = half size, "
      "no antialiasing; preview = full size, no antialiasing; final = full size, antialiasing "
      "threshold 0.05, depth 3. Reference: full size, every pixel supersampled (threshold 0, "
      "depth 4), " +
      format("%.2f", r.reference_seconds) +
      " s. A smaller image is compared "
      "after pixel replication. Bands: the nearest of the reference's " +
      std::to_string(r.reference_bands) +
      " flat colours (those covering at least 1% of it). "
      "max_trace_level is povgen's in every preset.\n\n"
      "| preset | size | POV-Ray (s) | RMSE | pixels in another band |\n|---|---|---:|---:|---:|\n";
  for (const RenderQualitySample& p : r.presets)
    md += "| " + p.preset + " | " + std::to_string(p.width) + "×" + std::to_string(p.height) +
          " | " + format("%.2f", p.seconds) + " | " + format("%.4f", p.rmse) + " | " +
          format("%.2f%%", 100.0 * p.band_mismatch) + " |\n";
  return md + "\n![rendering error](render_error.svg)\n\n";
}

}  // namespace

std::string report_markdown(const ReportResult& result, const ReportRun& c) {
  std::string md = "# toonwater: accuracy and cost\n\n";
  md += "Measured by `toonwater report` (" + std::string(c.size_name) + " run, " +
        std::to_string(std::thread::hardware_concurrency()) +
        " hardware threads). Raw numbers: [curvature_errors.csv](curvature_errors.csv), "
        "[pipeline.csv](pipeline.csv), [render_quality.csv](render_quality.csv).\n\n";
  md +=
      "## 1. Curvature error against run time\n\n"
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
      std::to_string(c.repeats) + " run(s) of the curvature stage.\n\n";
  for (const std::string& sampling : study_samplings)
    for (bool mean : {true, false})
      md += "![" + std::string(mean ? "H" : "K") + ", " + sampling + "](" +
            error_plot_name(sampling, mean) + ")\n";
  md += "\n";
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
    md += render_quality_section(
        *result.render_quality,
        c.scene + " (" + std::to_string(result.pipeline.front().vertices) + " vertices)", c.width,
        c.height);
  md += "## 4. Table 1: time per frame\n\n" + pipeline_table(result.pipeline, c.width, c.height);
  md += "\n## 5. Flow regions: the paper's criterion and the default\n\n" +
        flow_section(result, c.pixels_per_cell);
  if (!std::filesystem::exists(c.data_dir / "mantaflow-wake"))
    md += "\nThe sample simulation was not found in " + c.data_dir.string() +
          " (pass `--data DIR`).\n";
  return md;
}

}  // namespace toonwater::report
