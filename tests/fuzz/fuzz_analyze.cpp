// libFuzzer target for the analyzer behind the OBJ reader: whatever mesh a file holds (slivers,
// repeated corners, non-manifold fans, huge and tiny coordinates), analyze_mesh must not crash
// and no value it reports may be NaN or infinite (they reach CSV, PLY and scene files).
#include "analyzer/analysis.hpp"
#include "analyzer/readers/readers.hpp"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace {

void require_finite(const std::vector<double>& values) {
  for (const double v : values)
    if (!std::isfinite(v)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace toonwater;
  const readers::SourceFile file{"fuzz.obj", {reinterpret_cast<const char*>(data), size}};
  InputMesh input;
  try {
    input = readers::read_obj(file);
  } catch (const InputError&) {
    return 0;
  }
  // Small meshes only: the analysis is linear, large inputs would only slow the search down.
  if (input.mesh.triangles.empty() || input.mesh.positions.size() > 4096) return 0;
  const Analysis a = analyze_mesh(input.mesh, AnalyzeOptions{});
  const CurvatureField& c = a.curvature;
  for (const auto* values : {&c.area, &c.gaussian, &c.mean}) {
    require_finite(*values);
    if (values->size() != a.surface.positions.size()) std::abort();
  }
  for (const Vec3& n : c.normal)
    if (!n.allFinite()) std::abort();
  if (a.input_to_surface.size() != input.mesh.positions.size()) std::abort();
  if (!std::isfinite(a.flow.threshold)) std::abort();
  return 0;
}
