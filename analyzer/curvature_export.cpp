// CSV and PLY export of the curvature, one row per input vertex: input vertex i takes the values
// of analysis row input_to_surface[i]. Each file is formatted in blocks of rows (the CSV's on
// both cores) that go straight to an AtomicFileWriter.
// Values that are not finite (which the analysis should never produce) are written as 0, and
// PLY floats are clamped to the float range, so no output ever holds NaN or Inf.
#include "analyzer/curvature_export.hpp"

#include "common/atomic_file.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace toonwater {
namespace {

void check_consistent(const Analysis& analysis) {
  const std::size_t rows = analysis.surface.positions.size();
  const CurvatureField& c = analysis.curvature;
  const bool consistent =
      std::all_of(
          analysis.input_to_surface.begin(), analysis.input_to_surface.end(),
          [rows](std::int32_t s) { return s >= 0 && static_cast<std::size_t>(s) < rows; }) &&
      c.gaussian.size() == rows && c.mean.size() == rows && c.area.size() == rows &&
      analysis.flow.label.size() == rows && analysis.flow.field.size() == rows;
  if (!consistent)
    throw std::invalid_argument("curvature export: the analysis does not belong to the mesh");
}

double finite_or_zero(double value) { return std::isfinite(value) ? value : 0.0; }

// Nine shortest round-trip doubles (at most 24 characters each), a label and separators.
constexpr std::size_t max_csv_row_bytes = 9 * 24 + 4 + 10;

// Appends the CSV rows of input vertices [begin, end) to `text`, which has room for them.
void append_csv_rows(const Analysis& analysis, std::size_t begin, std::size_t end,
                     std::string& text) {
  const CurvatureField& c = analysis.curvature;
  char row[max_csv_row_bytes];
  for (std::size_t v = begin; v < end; ++v) {
    const std::size_t s = analysis.input_to_surface[v];
    const Vec3& p = analysis.surface.positions[s];
    const auto [k1, k2] = principal_curvatures(c.gaussian[s], c.mean[s]);
    const double values[8] = {p.x(), p.y(), p.z(), c.gaussian[s], c.mean[s], k1, k2, c.area[s]};
    char* out = row;
    for (const double value : values) {
      out = std::to_chars(out, row + max_csv_row_bytes, finite_or_zero(value)).ptr;
      *out++ = ',';
    }
    out = std::to_chars(out, row + max_csv_row_bytes, int{analysis.flow.label[s]}).ptr;
    *out++ = ',';
    out = std::to_chars(out, row + max_csv_row_bytes, finite_or_zero(analysis.flow.field[s])).ptr;
    *out++ = '\n';
    text.append(row, out);
  }
}

// A value as a PLY float: finite, and within the float range (a larger double would overflow
// to infinity).
float ply_float(double value) {
  constexpr double largest = std::numeric_limits<float>::max();
  return static_cast<float>(std::clamp(finite_or_zero(value), -largest, largest));
}

template <class T>
char* put_little_endian(char* out, T value) {
  static_assert(sizeof(T) == 4);
  auto bits = std::bit_cast<std::uint32_t>(value);
  for (int byte = 0; byte < 4; ++byte, bits >>= 8) *out++ = static_cast<char>(bits & 0xff);
  return out;
}

// Rows formatted and written per block: enough to keep both cores busy, small against the file.
constexpr std::size_t rows_per_block = 1 << 16;

}  // namespace

void write_curvature_csv(const std::filesystem::path& path, const Analysis& analysis) {
  check_consistent(analysis);
  AtomicFileWriter file(path);
  file.write("x,y,z,gaussian,mean,k1,k2,area,label,flow\n");
  const std::size_t n = analysis.input_to_surface.size();
  // Shortest round-trip formatting dominates the cost, so each block is split over the cores.
  std::vector<std::string> parts(chunk_count(std::min(n, rows_per_block)));
  for (std::size_t block = 0; block < n; block += rows_per_block) {
    const std::size_t rows = std::min(rows_per_block, n - block);
    parallel_chunks(rows, parts.size(), [&](std::size_t part, std::size_t begin, std::size_t end) {
      parts[part].clear();
      parts[part].reserve((end - begin) * max_csv_row_bytes);
      append_csv_rows(analysis, block + begin, block + end, parts[part]);
    });
    for (const std::string& part : parts) file.write(part);
  }
  file.commit();
}

void write_curvature_ply(const std::filesystem::path& path,
                         const std::vector<Triangle>& input_triangles, const Analysis& analysis) {
  check_consistent(analysis);
  const std::size_t n = analysis.input_to_surface.size();
  for (const Triangle& t : input_triangles)
    for (const std::int32_t index : t)
      if (index < 0 || static_cast<std::size_t>(index) >= n)
        throw std::invalid_argument("curvature export: a triangle indexes no input vertex");
  AtomicFileWriter file(path);
  file.write(
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment toonwater curvature per vertex; label: 1 ridge, -1 valley, 0 none; flow: the "
      "signed flow field, regions where |flow| >= 1\n"
      "element vertex " +
      std::to_string(n) +
      "\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property float gaussian\nproperty float mean\nproperty float k1\nproperty float k2\n"
      "property float area\nproperty float label\nproperty float flow\n"
      "element face " +
      std::to_string(input_triangles.size()) +
      "\n"
      "property list uchar int vertex_indices\n"
      "end_header\n");
  constexpr std::size_t vertex_bytes = 10 * 4;
  constexpr std::size_t face_bytes = 1 + 3 * 4;
  std::string block;
  block.reserve(rows_per_block * vertex_bytes);
  const CurvatureField& c = analysis.curvature;
  for (std::size_t first = 0; first < n; first += rows_per_block) {
    block.assign(std::min(rows_per_block, n - first) * vertex_bytes, '\0');
    char* out = block.data();
    for (std::size_t v = first; v < first + block.size() / vertex_bytes; ++v) {
      const std::size_t s = analysis.input_to_surface[v];
      const Vec3& p = analysis.surface.positions[s];
      const auto [k1, k2] = principal_curvatures(c.gaussian[s], c.mean[s]);
      const double values[10] = {p.x(),
                                 p.y(),
                                 p.z(),
                                 c.gaussian[s],
                                 c.mean[s],
                                 k1,
                                 k2,
                                 c.area[s],
                                 static_cast<double>(analysis.flow.label[s]),
                                 analysis.flow.field[s]};
      for (const double value : values) out = put_little_endian(out, ply_float(value));
    }
    file.write(block);
  }
  for (std::size_t first = 0; first < input_triangles.size(); first += rows_per_block) {
    const std::size_t count = std::min(rows_per_block, input_triangles.size() - first);
    block.assign(count * face_bytes, '\0');
    char* out = block.data();
    for (std::size_t f = first; f < first + count; ++f) {
      *out++ = 3;
      for (const std::int32_t index : input_triangles[f]) out = put_little_endian(out, index);
    }
    file.write(block);
  }
  file.commit();
}

}  // namespace toonwater
