#include "report/report_csv.hpp"

#include "report/number_format.hpp"

namespace toonwater::report {

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
  std::string csv =
      "input,vertices,analysis_one_ring_s,analysis_jet_s,scene_writing_s,povray_s,total_s\n";
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

std::string ripple_csv(const std::vector<RippleRow>& rows) {
  std::string s = "criterion,n,jittered,crest_ridge,trough_valley,calm_labelled,labelled_share\n";
  for (const RippleRow& r : rows)
    s += r.criterion + "," + std::to_string(r.n) + "," + (r.jittered ? "1" : "0") + "," +
         g(r.coverage.crest_ridge) + "," + g(r.coverage.trough_valley) + "," +
         g(r.coverage.calm_labelled) + "," + g(r.coverage.labelled_share) + "\n";
  return s;
}

std::string render_quality_csv(const RenderQualityResult& r) {
  std::string csv = "preset,width,height,seconds,rmse,band_mismatch\n";
  for (const RenderQualitySample& p : r.presets)
    csv += p.preset + "," + std::to_string(p.width) + "," + std::to_string(p.height) + "," +
           format("%.6g", p.seconds) + "," + format("%.6g", p.rmse) + "," +
           format("%.6g", p.band_mismatch) + "\n";
  return csv;
}

}  // namespace toonwater::report
