// read_mesh: loads the file (one pread per core), picks the reader by extension, and checks that a
// mesh came out. Also the parsing helpers the format readers share (readers/readers.hpp).
#include "analyzer/mesh_reader.hpp"

#include "analyzer/readers/readers.hpp"
#include "analyzer/readers/vdb/vdb_module.hpp"
#include "common/parallel.hpp"
#include "common/printable_text.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <system_error>
#include <vector>

namespace toonwater {
namespace readers {

void fail(const SourceFile& file, std::string_view message) {
  throw InputError(file.name + ": " + std::string(message));
}

void fail_at_line(const SourceFile& file, std::size_t line, std::string_view message) {
  throw InputError(file.name + ":" + std::to_string(line) + ": " + std::string(message));
}

std::string quote(std::string_view field) {
  constexpr std::size_t longest_field_shown = 40;
  // Built with += only: GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
  std::string quoted = "'";
  quoted += printable_text(field, longest_field_shown);
  quoted += '\'';
  return quoted;
}

bool LineReader::next(std::string_view& line) {
  if (rest_.empty()) return false;
  const std::size_t end = rest_.find('\n');
  if (end == std::string_view::npos) {
    line = rest_;
    // Empty, but still pointing at the end of the text, where a binary body read from here
    // starts: a null pointer would make any offset from it undefined.
    rest_ = rest_.substr(rest_.size());
  } else {
    line = rest_.substr(0, end);
    rest_.remove_prefix(end + 1);
  }
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  ++line_number_;
  return true;
}

std::string_view strip_comment(std::string_view line) { return line.substr(0, line.find('#')); }

namespace {
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// std::from_chars takes no leading '+'; text formats occasionally write one.
std::string_view without_plus(std::string_view field) {
  if (field.size() > 1 && field[0] == '+' && field[1] != '-' && field[1] != '+')
    field.remove_prefix(1);
  return field;
}
}  // namespace

std::string_view Fields::next() {
  std::size_t begin = 0;
  while (begin < rest_.size() && is_space(rest_[begin])) ++begin;
  std::size_t end = begin;
  while (end < rest_.size() && !is_space(rest_[end])) ++end;
  const std::string_view field = rest_.substr(begin, end - begin);
  rest_.remove_prefix(end);
  return field;
}

bool Fields::at_end() {
  while (!rest_.empty() && is_space(rest_.front())) rest_.remove_prefix(1);
  return rest_.empty();
}

std::optional<double> parse_double(std::string_view field) {
  field = without_plus(field);
  double value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (end != field.data() + field.size()) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    // from_chars leaves the value unset on overflow and on underflow alike; strtod tells them
    // apart (±HUGE_VAL, then rejected as infinite, or a denormal or zero, which is fine).
    const std::string copy(field);
    return std::strtod(copy.c_str(), nullptr);
  }
  if (error != std::errc{}) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_integer(std::string_view field) {
  field = without_plus(field);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc{} || end != field.data() + field.size()) return std::nullopt;
  return value;
}

double parse_coordinate(const SourceFile& file, std::size_t line, std::string_view field) {
  const std::optional<double> value = parse_double(field);
  if (!value) fail_at_line(file, line, "malformed number " + quote(field));
  if (!std::isfinite(*value))
    fail_at_line(file, line, "coordinate " + quote(field) + " is NaN or infinite");
  return *value;
}

Vec3 read_point(const SourceFile& file, std::size_t line, Fields& fields) {
  double xyz[3];
  for (int axis = 0; axis < 3; ++axis) {
    const std::string_view field = fields.next();
    if (field.empty())
      fail_at_line(file, line, "vertex has " + std::to_string(axis) + " coordinates, expected 3");
    xyz[axis] = parse_coordinate(file, line, field);
  }
  return {xyz[0], xyz[1], xyz[2]};
}

std::size_t capped_reserve(std::uint64_t declared, std::size_t remaining_bytes,
                           std::size_t min_record_bytes) {
  return static_cast<std::size_t>(
      std::min<std::uint64_t>(declared, remaining_bytes / min_record_bytes));
}

void add_polygon(TriangleMesh& mesh, std::span<const std::int32_t> corners) {
  for (std::size_t i = 1; i + 1 < corners.size(); ++i)
    mesh.triangles.push_back({corners[0], corners[i], corners[i + 1]});
}

[[noreturn]] void fail_errno(const SourceFile& file, std::string_view what, int error) {
  readers::fail(file, std::string(what) + ": " + std::generic_category().message(error));
}

// The whole file, read with one pread() per core into its own part of the buffer (more calls
// only if the kernel returns a part in pieces): the copy and the first touch of the buffer's
// pages are the cost, and they split over the cores.
std::unique_ptr<char[]> load_file(const SourceFile& file, std::size_t& size) {
  // Non-blocking: a FIFO would otherwise wait for a writer before the check below refuses it.
  const int fd = ::open(file.name.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) fail_errno(file, "cannot open", errno);
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};

  struct stat info {};
  if (::fstat(fd, &info) != 0) fail_errno(file, "cannot read", errno);
  if (!S_ISREG(info.st_mode)) readers::fail(file, "is not a regular file");
  // The file is read whole: one larger than the machine's memory (a sparse file, a disk image)
  // is refused here rather than left to the allocator or the kernel's OOM killer.
  const std::uint64_t memory = static_cast<std::uint64_t>(::sysconf(_SC_PHYS_PAGES)) *
                               static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
  if (memory > 0 && static_cast<std::uint64_t>(info.st_size) > memory)
    readers::fail(file, "is " + std::to_string(static_cast<std::uint64_t>(info.st_size) >> 30) +
                            " GiB, more than this machine's memory (" +
                            std::to_string(memory >> 30) + " GiB); no mesh file is that large");
  size = static_cast<std::size_t>(info.st_size);
  auto bytes = std::make_unique_for_overwrite<char[]>(size);
  constexpr std::size_t min_part_bytes = std::size_t{1} << 20;
  const std::size_t parts = chunk_count(size, min_part_bytes);
  std::vector<std::size_t> part_end(parts);  // where each part's data ends (short: the file shrank)
  std::vector<int> part_error(parts, 0);
  parallel_chunks(size, parts, [&](std::size_t part, std::size_t begin, std::size_t end) {
    std::size_t done = begin;
    while (done < end) {
      const ssize_t n = ::pread(fd, bytes.get() + done, end - done, static_cast<off_t>(done));
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        part_error[part] = errno;
        break;
      }
      if (n == 0) break;
      done += static_cast<std::size_t>(n);
    }
    part_end[part] = done;
  });
  for (std::size_t part = 0; part < parts; ++part) {
    if (part_error[part] != 0) fail_errno(file, "cannot read", part_error[part]);
    if (part_end[part] != size * (part + 1) / parts) {  // the file shrank while we read it
      size = part_end[part];
      break;
    }
  }
  return bytes;
}

std::string lowercase_extension(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

void check_regular_file(const SourceFile& file) {
  struct stat info {};
  if (::stat(file.name.c_str(), &info) != 0) fail_errno(file, "cannot open", errno);
  if (!S_ISREG(info.st_mode)) fail(file, "is not a regular file");
}

}  // namespace readers

namespace {

using readers::SourceFile;

// An OpenVDB level set, meshed (readers/vdb/vdb_module.hpp): the module opens the file.
InputMesh read_level_set(const SourceFile& file, const LevelSetOptions& options) {
  readers::check_regular_file(file);
  const VdbModule& module = vdb_module();
  MeshedLevelSet meshed;
  try {
    meshed = module.mesh_level_set(file.name, options.grid, options.adaptivity);
  } catch (const std::runtime_error& e) {
    readers::fail(file, e.what());
  }
  for (const Vec3& p : meshed.mesh.positions)
    if (!p.allFinite())
      readers::fail(file, "grid '" + meshed.grid + "' meshes to a non-finite point");
  InputMesh result;
  result.polygon_count = meshed.mesh.triangles.size();
  result.mesh = std::move(meshed.mesh);
  return result;
}

}  // namespace

InputMesh read_mesh(const std::filesystem::path& path, const LevelSetOptions& level_set) {
  SourceFile file{path.string(), {}};
  const std::string extension = readers::lowercase_extension(path);
  if (extension == ".vdb") {
    InputMesh result = read_level_set(file, level_set);
    if (result.mesh.triangles.empty())
      throw EmptyMeshError(file.name + ": its level set has no zero crossing (no surface)");
    return result;
  }
  InputMesh (*read)(const SourceFile&) = nullptr;
  if (extension == ".obj")
    read = readers::read_obj;
  else if (extension == ".off")
    read = readers::read_off;
  else if (extension == ".ply")
    read = readers::read_ply;
  else if (extension == ".stl")
    read = readers::read_stl;
  else if (extension == ".gz" && readers::lowercase_extension(path.stem()) == ".bobj")
    read = readers::read_bobj;
  else if (extension == ".bobj")
    read = readers::read_flip_bobj;
  else if (extension == ".vtk")
    read = readers::read_vtk;
  else if (extension.empty())
    readers::fail(file,
                  "has no extension to tell its format "
                  "(expected .obj, .off, .ply, .stl, .vtk, .bobj.gz, .bobj or .vdb)");
  else
    readers::fail(file, "unknown mesh format " + readers::quote(extension) +
                            " (expected .obj, .off, .ply, .stl, .vtk, .bobj.gz, .bobj or .vdb)");

  std::size_t size = 0;
  const std::unique_ptr<char[]> bytes = readers::load_file(file, size);
  file.bytes = std::string_view(bytes.get(), size);
  InputMesh result = read(file);
  if (result.mesh.triangles.empty()) throw EmptyMeshError(file.name + ": contains no faces");
  return result;
}

}  // namespace toonwater
