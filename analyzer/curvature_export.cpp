// CSV and PLY export of the curvature, one row per input vertex: input vertex i takes the values
// of analysis row input_to_surface[i]. Each file is built in one string and written atomically.
// Values that are not finite (which the analysis should never produce) are written as 0, and
// PLY floats are clamped to the float range, so no output ever holds NaN or Inf.
#include "analyzer/curvature_export.hpp"

#include "analyzer/atomic_file.hpp"
#include "analyzer/parallel.hpp"

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

void check_belongs_to(const TriangleMesh& input, const Analysis& analysis) {
  const std::size_t rows = analysis.surface.positions.size();
  const CurvatureField& c = analysis.curvature;
  const bool consistent = analysis.input_to_surface.size() == input.positions.size() &&
                          c.gaussian.size() == rows && c.mean.size() == rows &&
                          c.k1.size() == rows && c.k2.size() == rows && c.area.size() == rows &&
                          analysis.flow.label.size() == rows;
  if (!consistent)
    throw std::invalid_argument("curvature export: the analysis does not belong to the mesh");
}

double finite_or_zero(double value) { return std::isfinite(value) ? value : 0.0; }

// Eight shortest round-trip doubles (at most 24 characters each), a label and separators.
constexpr std::size_t max_csv_row_bytes = 8 * 24 + 4 + 9;

// Appends the CSV rows of input vertices [begin, end) to `text`, which has room for them.
void append_csv_rows(const TriangleMesh& input, const Analysis& analysis, std::size_t begin,
                     std::size_t end, std::string& text) {
  const CurvatureField& c = analysis.curvature;
  char row[max_csv_row_bytes];
  for (std::size_t v = begin; v < end; ++v) {
    const std::size_t s = analysis.input_to_surface[v];
    const double values[8] = {input.positions[v].x(), input.positions[v].y(),
                              input.positions[v].z(), c.gaussian[s], c.mean[s], c.k1[s],
                              c.k2[s], c.area[s]};
    char* out = row;
    for (const double value : values) {
      out = std::to_chars(out, row + max_csv_row_bytes, finite_or_zero(value)).ptr;
      *out++ = ',';
    }
    out = std::to_chars(out, row + max_csv_row_bytes, int{analysis.flow.label[s]}).ptr;
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

}  // namespace

std::string curvature_csv(const TriangleMesh& input, const Analysis& analysis) {
  check_belongs_to(input, analysis);
  const std::size_t n = input.positions.size();
  // Shortest round-trip formatting dominates the cost, so the rows are split over the cores.
  // The first part is the result: it has room for every row (pages never touched cost nothing)
  // and takes the other parts' rows after its own, which saves a copy of its half.
  std::vector<std::string> parts(worker_count(n));
  parts[0].reserve(64 + n * max_csv_row_bytes);
  parts[0] = "x,y,z,gaussian,mean,k1,k2,area,label\n";
  parallel_chunks(n, parts.size(), [&](std::size_t part, std::size_t begin, std::size_t end) {
    if (part != 0) parts[part].reserve((end - begin) * max_csv_row_bytes);
    append_csv_rows(input, analysis, begin, end, parts[part]);
  });
  for (std::size_t part = 1; part < parts.size(); ++part) parts[0] += parts[part];
  return std::move(parts[0]);
}

std::string curvature_ply(const TriangleMesh& input, const Analysis& analysis) {
  check_belongs_to(input, analysis);
  const std::size_t n = input.positions.size();
  const std::size_t faces = input.triangles.size();
  const std::string header =
      "ply\n"
      "format binary_little_endian 1.0\n"
      "comment toonwater curvature per vertex; label: 1 ridge, -1 valley, 0 none\n"
      "element vertex " + std::to_string(n) + "\n"
      "property float x\nproperty float y\nproperty float z\n"
      "property float gaussian\nproperty float mean\nproperty float k1\nproperty float k2\n"
      "property float area\nproperty float label\n"
      "element face " + std::to_string(faces) + "\n"
      "property list uchar int vertex_indices\n"
      "end_header\n";
  constexpr std::size_t vertex_bytes = 9 * 4;
  constexpr std::size_t face_bytes = 1 + 3 * 4;

  std::string bytes(header.size() + n * vertex_bytes + faces * face_bytes, '\0');
  char* out = std::copy(header.begin(), header.end(), bytes.data());
  const CurvatureField& c = analysis.curvature;
  for (std::size_t v = 0; v < n; ++v) {
    const std::size_t s = analysis.input_to_surface[v];
    const double values[9] = {input.positions[v].x(), input.positions[v].y(),
                              input.positions[v].z(), c.gaussian[s], c.mean[s], c.k1[s],
                              c.k2[s], c.area[s], static_cast<double>(analysis.flow.label[s])};
    for (const double value : values) out = put_little_endian(out, ply_float(value));
  }
  for (const Triangle& t : input.triangles) {
    *out++ = 3;
    for (const std::int32_t index : t) out = put_little_endian(out, index);
  }
  return bytes;
}

void write_curvature_csv(const std::filesystem::path& path, const TriangleMesh& input,
                         const Analysis& analysis) {
  write_file_atomically(path, curvature_csv(input, analysis));
}

void write_curvature_ply(const std::filesystem::path& path, const TriangleMesh& input,
                         const Analysis& analysis) {
  write_file_atomically(path, curvature_ply(input, analysis));
}

}  // namespace toonwater
