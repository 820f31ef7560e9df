// FLIP Fluids' whitewater particles, `bakefiles/{foam,bubble,spray,dust}NNNNNN.wwp`
// (DiffuseParticleSimulation::_getDiffuseParticleFileDataWWP, src/engine/
// diffuseparticlesimulation.cpp; read by the add-on's import_wwp), little-endian:
//   256 uint32: for each particle id b (0–255, the add-on's display subsets), the number of
//               particles with ids up to b, minus one (so 2^32 − 1 while none);
//   n × 3 float32 positions, sorted by id, n the last entry plus one;
// and nothing after. An empty file holds no particles. Positions are in world units (the
// engine's domain scale and offset applied). The file does not say its kind: its name does.
#include "analyzer/readers/readers.hpp"

#include <cstdint>
#include <string>

namespace toonwater::readers {
namespace {

constexpr std::size_t id_count = 256;
constexpr std::size_t table_bytes = 4 * id_count;

}  // namespace

ParticleSet read_wwp(const SourceFile& file, ParticleKind kind) {
  ParticleSet out;
  if (file.bytes.empty()) return out;
  if (file.bytes.size() < table_bytes)
    fail(file, "truncated: a whitewater file starts with " + std::to_string(table_bytes) +
                   " bytes of id counts, the file has " + std::to_string(file.bytes.size()) +
                   " (byte offset " + std::to_string(file.bytes.size()) + ")");
  std::uint64_t previous = 0;
  for (std::size_t id = 0; id < id_count; ++id) {
    // Stored minus one, modulo 2^32: 0xFFFFFFFF is zero particles.
    const std::uint64_t through =
        (std::uint64_t{little_endian<std::uint32_t>(file.bytes.data() + 4 * id)} + 1) & 0xFFFFFFFFu;
    if (through < previous)
      fail(file, "id count " + std::to_string(id) + " (" + std::to_string(through) +
                     ") is below the one before it (" + std::to_string(previous) +
                     "): not a whitewater file (byte offset " + std::to_string(4 * id) + ")");
    previous = through;
  }
  const std::uint64_t count = previous;
  const std::uint64_t expected = table_bytes + 12 * count;
  if (file.bytes.size() != expected)
    fail(file, "its id counts promise " + std::to_string(count) + " particles (" +
                   std::to_string(expected) + " bytes), the file has " +
                   std::to_string(file.bytes.size()) + " bytes");
  out.positions.reserve(count);
  const char* record = file.bytes.data() + table_bytes;
  for (std::uint64_t i = 0; i < count; ++i, record += 12) {
    const Vec3 p(little_endian<float>(record), little_endian<float>(record + 4),
                 little_endian<float>(record + 8));
    if (!p.allFinite())
      fail(file, "coordinate is NaN or infinite (particle " + std::to_string(i) + ")");
    out.positions.push_back(p);
  }
  out.kinds.assign(out.positions.size(), kind);
  return out;
}

}  // namespace toonwater::readers
