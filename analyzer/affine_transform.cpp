// Affine maps of mesh positions. A is singular, for our purposes, when
// |det A| <= 1e-12 · |row 0| |row 1| |row 2|: by Hadamard's inequality |det A| never exceeds the
// product of the row lengths (equality for orthogonal rows), so the ratio measures how close A
// comes to flattening space whatever its scale — a uniform scale by 1e-6 passes, a matrix whose
// rows are (numerically) dependent does not.
#include "analyzer/affine_transform.hpp"

#include "analyzer/mesh_reader.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace toonwater {
namespace {

constexpr double singular_ratio = 1e-12;

// det A / (|a₀| |a₁| |a₂|) for the rows aᵢ of A: its sign is det A's, and |·| ≤ 1 measures how
// far A is from flattening whatever its scale (det A itself overflows at a scale of 1e103 and
// underflows at 1e-108, where the map is still exact). 0 where a row is zero.
double normalised_determinant(const Eigen::Matrix3d& linear) {
  Eigen::Matrix3d rows = linear;
  for (int r = 0; r < 3; ++r) {
    const double scale = rows.row(r).cwiseAbs().maxCoeff();  // first by the largest: no overflow
    if (scale == 0.0) return 0.0;
    rows.row(r) /= scale;
    rows.row(r).normalize();
  }
  return rows.determinant();
}

AffineTransform validated(const AffineTransform& transform) {
  if (!transform.linear.allFinite() || !transform.translation.allFinite())
    throw std::invalid_argument("transform: an entry is NaN or infinite");
  const double det = normalised_determinant(transform.linear);
  if (!(std::abs(det) > singular_ratio)) {
    std::ostringstream message;
    message << "transform: the linear part is singular (its rows' normalised determinant is " << det
            << "): it would flatten the mesh";
    throw std::invalid_argument(message.str());
  }
  return transform;
}

}  // namespace

AffineTransform affine_from_rows(std::span<const double, 12> rows) {
  AffineTransform transform;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) transform.linear(r, c) = rows[4 * r + c];
    transform.translation[r] = rows[4 * r + 3];
  }
  return validated(transform);
}

AffineTransform scale_then_translate(double scale, const Vec3& translation) {
  return validated({scale * Eigen::Matrix3d::Identity(), translation});
}

void apply_transform(const AffineTransform& transform, TriangleMesh& mesh,
                     const std::filesystem::path& source) {
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    Vec3& p = mesh.positions[v];
    p = transform.linear * p + transform.translation;
    // Finite entries and a finite position can still give inf (1e300 scaled by 1e10): the
    // analysis would take it for a point at infinity and write zeros where the user expects data.
    if (!p.allFinite())
      throw InputError(source.string() + ": vertex " + std::to_string(v) +
                       " lies beyond the largest double after the transform");
  }
  if (normalised_determinant(transform.linear) < 0)
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
}

}  // namespace toonwater
