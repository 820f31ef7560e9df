// `toonwater report`: runs the studies and the pipeline timings and writes their CSV, SVG and
// Markdown (report_csv, report_plots, report_markdown); see report.hpp. The conclusions ("when
// each estimator is the better choice") are computed from the samples of this run
// (sample_analysis), not written in advance.
#include "report/report.hpp"

#include "corpus/analytic_surfaces.hpp"
#include "common/atomic_file.hpp"
#include "common/temporary_name.hpp"
#include "analyzer/obj_writer.hpp"
#include "report/report_csv.hpp"
#include "report/report_markdown.hpp"
#include "report/report_plots.hpp"

#include <exception>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <utility>

namespace toonwater::report {
namespace {

namespace fs = std::filesystem;

std::vector<std::size_t> study_targets(ReportSize size) {
  switch (size) {
    case ReportSize::quick:
      return {1000, 4000, 16000};
    case ReportSize::standard:
      return {1000, 4000, 16000, 64000, 250000};
    case ReportSize::full:
      return {1000, 4000, 16000, 64000, 250000, 1000000};
  }
  return {};
}

// The paper's frame had 55,091 vertices; 235² = 55,225.
fs::path write_height_field(const fs::path& dir, int side) {
  TriangleMesh m = make_wave_field(side, 0.1, 6.0, 1.0).mesh;
  // Height field in the xz plane, y up, as toonwater's default axis: y and z swap, and so the
  // winding turns to keep the faces up.
  for (Vec3& p : m.positions) std::swap(p.y(), p.z());
  for (Triangle& t : m.triangles) std::swap(t[1], t[2]);
  const fs::path path = dir / ("height_field_" + std::to_string(side * side) + ".obj");
  write_obj(path, m);
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

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (!in && !in.eof()) throw OutputError(path.string() + ": cannot read");
  return bytes;
}

// The plot's place when the render quality could not be measured: the reason, in words.
std::string not_measured_svg(const std::string& reason) {
  std::string text;
  for (const char c : reason.substr(0, 200))
    text += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"640\" height=\"40\">"
         "<text x=\"10\" y=\"25\" font-family=\"sans-serif\" font-size=\"12\">Not measured: " +
         text + "</text></svg>\n";
}

}  // namespace

ReportResult write_report(const ReportOptions& options) {
  auto progress = [&](const std::string& line) {
    if (options.progress) options.progress(line);
  };
  // Scratch meshes and scenes go in a directory of the run's own, made fresh beside the
  // report (a user's DIR/work is no concern of it), and go whether the run succeeds or throws.
  fs::create_directories(options.out_dir);
  remove_stale_temporaries(options.out_dir);  // of report runs that were killed
  const fs::path work = options.out_dir / temporary_name("report-work");
  if (!fs::create_directory(work))
    throw OutputError(work.string() + ": cannot create the report's work directory: it exists");
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
  // A part that fails (POV-Ray missing or failing) is reported as not measured, the rest still
  // reports, and the run then ends with that part's error: the exit code says that not all was
  // measured. Sample data that is absent is only noted: it is optional.
  std::exception_ptr first_failure;
  progress("render quality: presets and reference render of the " + inputs.front().name);
  try {
    result.render_quality = measure_render_quality(work / "scene_0", width, height);
  } catch (const std::exception& e) {
    result.render_quality_failure = e.what();
    first_failure = std::current_exception();
  }

  progress("flow criteria: analytic ripples");
  result.ripples =
      run_ripple_study(options.size == ReportSize::quick ? std::vector<int>{81, 161}
                                                         : std::vector<int>{81, 161, 321});
  const fs::path wake_frames = options.data_dir / "mantaflow-wake" / "water_####.obj";
  const double pixels_per_cell = options.size == ReportSize::quick ? 2.0 : 8.0;
  if (!fs::exists(options.data_dir / "mantaflow-wake" / "water_0001.obj")) {
    result.flow_sequence_failure =
        "the sample simulation was not found in " + options.data_dir.string();
  } else {
    progress("flow criteria: mantaflow-wake from above");
    try {
      // A quick run measures frames 10–15 (the wake at its busiest) at 2 pixels a cell.
      std::optional<FrameRange> frames;
      if (options.size == ReportSize::quick) frames = FrameRange{10, 15};
      // The pictures go to the work directory first, and into DIR with the other outputs.
      result.flow_sequence = run_sequence_flow_study(
          fs::absolute(wake_frames).string(), Axis::z, work, work, pixels_per_cell,
          {FlowCriterion::mean, FlowCriterion::paper}, frames);
    } catch (const std::exception& e) {
      result.flow_sequence_failure = e.what();
      if (!first_failure) first_failure = std::current_exception();
    }
  }

  // Every output at once (OutputBatch): DIR holds the earlier report or this one, never a mix.
  // A part not measured still replaces its files, with what was (not) measured, so that no
  // earlier run's numbers stand beside this run's report.
  OutputBatch batch;
  for (SequenceFlowStudy& sequence : result.flow_sequence) {
    const fs::path picture = options.out_dir / sequence.picture.filename();
    write_file_atomically(picture, read_bytes(sequence.picture));
    sequence.picture = picture;
  }
  write_file_atomically(options.out_dir / "flow_ripples.csv", ripple_csv(result.ripples));
  write_file_atomically(options.out_dir / "curvature_errors.csv", study_csv(result.study));
  write_file_atomically(options.out_dir / "pipeline.csv", pipeline_csv(result.pipeline));
  write_file_atomically(options.out_dir / "render_quality.csv",
                        render_quality_csv(result.render_quality.value_or(RenderQualityResult{})));
  write_file_atomically(options.out_dir / "render_error.svg",
                        result.render_quality ? render_quality_plot(*result.render_quality)
                                              : not_measured_svg(result.render_quality_failure));
  for (const std::string& sampling : study_samplings)
    for (bool mean : {true, false})
      write_file_atomically(options.out_dir / error_plot_name(sampling, mean),
                            error_plot(result.study, sampling, mean));

  ReportRun run;
  run.size_name = options.size == ReportSize::quick      ? "quick"
                  : options.size == ReportSize::standard ? "standard"
                                                         : "full";
  run.repeats = study.repeats;
  run.scene = inputs.front().name;
  run.width = width;
  run.height = height;
  run.pixels_per_cell = pixels_per_cell;
  run.data_dir = options.data_dir;
  write_file_atomically(options.out_dir / "report.md", report_markdown(result, run));
  batch.commit();
  if (first_failure) std::rethrow_exception(first_failure);
  return result;
}

}  // namespace toonwater::report
