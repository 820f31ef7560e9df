// Table 1 timings; see pipeline_timing.hpp. The scene is povgen's default (flow regions and
// outlines on, the paper's shading); POV-Ray renders it with one job, so its time is the
// single-frame figure the paper reports.
#include "report/pipeline_timing.hpp"

#include "analyzer/analysis.hpp"
#include "analyzer/mesh_reader.hpp"
#include "pipeline/generate_scene.hpp"
#include "render/render.hpp"

#include <algorithm>
#include <vector>

namespace toonwater::report {
namespace {

double median_analysis_seconds(const TriangleMesh& mesh, Axis up, Estimator estimator) {
  AnalyzeOptions options;
  options.flow.up = up;
  options.estimator = estimator;
  std::vector<double> seconds;
  for (int run = 0; run < 3; ++run) {
    const Analysis a = analyze_mesh(mesh, options);
    seconds.push_back(a.times.weld + a.times.topology + a.times.curvature + a.times.flow);
  }
  std::sort(seconds.begin(), seconds.end());
  return seconds[1];
}

}  // namespace

PipelineTiming time_pipeline(const PipelineInput& input, const std::filesystem::path& work_dir,
                             int width, int height) {
  PipelineTiming t;
  t.name = input.name;
  const InputMesh mesh = read_mesh(input.mesh);
  t.vertices = mesh.mesh.positions.size();
  t.analysis_one_ring = median_analysis_seconds(mesh.mesh, input.up, Estimator::one_ring);
  t.analysis_jet = median_analysis_seconds(mesh.mesh, input.up, Estimator::jet);

  SceneConfig config;
  config.render.width = width;
  config.render.height = height;
  PovgenRequest request;
  request.water_pattern = std::filesystem::absolute(input.mesh).string();
  request.up = input.up;
  request.out_dir = work_dir;
  const PovgenReport written = generate_scene(config, request, {}, nullptr);
  t.scene_writing = written.write_seconds;

  RenderRequest render;
  render.scene_dir = work_dir;
  const RenderReport rendered = render_frames(render, {});
  // A single-frame povgen scene renders to frame.png (scene.ini's Output_File_Name).
  if (!rendered.failures.empty())
    t.povray_failure = rendered.failures[0].message;
  else if (rendered.rendered != 1 || !std::filesystem::is_regular_file(work_dir / "frame.png"))
    t.povray_failure = "POV-Ray wrote no image";
  else
    t.povray = rendered.seconds;
  return t;
}

}  // namespace toonwater::report
