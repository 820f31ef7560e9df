// libFuzzer target for the FLIP Fluids whitewater reader (readers::read_wwp). Any input must
// either give particles with finite positions, one kind each (and one velocity each, if any), or
// throw InputError; a crash, a
// sanitizer report, a leak, another exception or a broken set is a finding.
#include "analyzer/readers/readers.hpp"

#include <cstddef>
#include <cstdint>
#include <cstdlib>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace toonwater;
  const readers::SourceFile file{"fuzz", {reinterpret_cast<const char*>(data), size}};
  try {
    const ParticleSet result = readers::read_wwp(file, ParticleKind::foam);
    if (result.kinds.size() != result.positions.size()) std::abort();
    if (!result.velocities.empty() && result.velocities.size() != result.positions.size())
      std::abort();
    for (const Vec3& p : result.positions)
      if (!p.allFinite()) std::abort();
  } catch (const InputError&) {
    // Rejected with a message: the expected outcome for most inputs.
  }
  return 0;
}
