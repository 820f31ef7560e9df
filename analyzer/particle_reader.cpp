// read_particles (particles.hpp): the format from the file's extension, FLIP Fluids' kind from
// the file's name.
#include "analyzer/particles.hpp"

#include "analyzer/readers/readers.hpp"
#include "analyzer/readers/vdb/vdb_module.hpp"

#include <algorithm>
#include <cctype>
#include <string>

namespace toonwater {
namespace {

using readers::SourceFile;

// FLIP Fluids names a whitewater file by its kind and frame: "foam000012.wwp" (any case).
ParticleKind whitewater_kind(const SourceFile& file, const std::filesystem::path& path) {
  std::string stem = path.stem().string();
  std::transform(stem.begin(), stem.end(), stem.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const std::size_t digits = stem.find_first_of("0123456789");
  const std::string kind = stem.substr(0, digits);
  const bool frame = digits != std::string::npos &&
                     stem.find_first_not_of("0123456789", digits) == std::string::npos;
  if (frame && kind == "foam") return ParticleKind::foam;
  if (frame && kind == "bubble") return ParticleKind::bubble;
  if (frame && kind == "spray") return ParticleKind::spray;
  if (frame && kind == "dust") return ParticleKind::dust;
  readers::fail(file,
                "a whitewater file's name says its kind (foam, bubble, spray or dust, then the "
                "frame: foam000012.wwp)");
}

ParticleSet read_point_grid(const SourceFile& file) {
  readers::check_regular_file(file);
  const VdbModule& module = vdb_module();
  ParticleSet particles;
  try {
    particles = module.read_point_grid(file.name);
  } catch (const std::exception& e) {
    readers::fail(file, e.what());
  }
  return particles;
}

}  // namespace

std::string_view kind_name(ParticleKind kind) {
  switch (kind) {
    case ParticleKind::spray:
      return "spray";
    case ParticleKind::foam:
      return "foam";
    case ParticleKind::bubble:
      return "bubble";
    case ParticleKind::dust:
      return "dust";
    case ParticleKind::other:
      break;
  }
  return "other";
}

std::size_t count_of(const ParticleSet& particles, ParticleKind kind) {
  return static_cast<std::size_t>(std::count(particles.kinds.begin(), particles.kinds.end(), kind));
}

ParticleSet read_particles(const std::filesystem::path& path) {
  SourceFile file{path.string(), {}};
  const std::string extension = readers::lowercase_extension(path);
  if (extension == ".vdb") return read_point_grid(file);
  if (extension != ".wwp")
    readers::fail(
        file, "unknown particle format " + readers::quote(extension) + " (expected .vdb or .wwp)");
  const ParticleKind kind = whitewater_kind(file, path);
  std::size_t size = 0;
  const std::unique_ptr<char[]> bytes = readers::load_file(file, size);
  file.bytes = std::string_view(bytes.get(), size);
  return readers::read_wwp(file, kind);
}

}  // namespace toonwater
