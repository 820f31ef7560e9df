// libFuzzer target for one strict mesh reader (readers/readers.hpp), chosen at build time by
// TOONWATER_FUZZ_READER (read_obj, read_off, read_ply, read_stl, read_vtk, read_bobj or
// read_flip_bobj). Any input must either give a mesh whose triangles index its vertices and whose
// coordinates are finite, or throw InputError; a crash, a sanitizer report, a leak, another
// exception or a broken mesh is a finding.
#include "analyzer/readers/readers.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace toonwater;
  const readers::SourceFile file{"fuzz", {reinterpret_cast<const char*>(data), size}};
  try {
    const InputMesh result = readers::TOONWATER_FUZZ_READER(file);
    const auto vertices = static_cast<std::int64_t>(result.mesh.positions.size());
    for (const Vec3& p : result.mesh.positions)
      if (!p.allFinite()) std::abort();
    for (const auto& triangle : result.mesh.triangles)
      for (const std::int32_t corner : triangle)
        if (corner < 0 || corner >= vertices) std::abort();
    if (result.mesh.triangles.size() < result.polygon_count) std::abort();
  } catch (const InputError&) {
    // Rejected with a message: the expected outcome for most inputs.
  }
  return 0;
}
