#include "cli/transform_options.hpp"

#include "cli/validators.hpp"

#include "analyzer/mesh_reader.hpp"

#include <stdexcept>

namespace toonwater::cli {

void add_transform_options(CLI::App& cmd, TransformArgs& args) {
  CLI::Option* rows =
      cmd.add_option("--transform", args.rows,
                     "Map the mesh to world coordinates by x -> A x + b, given as the 3x4 matrix "
                     "[A | b] row by row: a00,a01,a02,b0,a10,a11,a12,b1,a20,a21,a22,b2")
          ->expected(12)
          ->delimiter(',')
          ->check(FiniteNumber);
  cmd.add_option("--scale", args.scale,
                 "S in the map x -> S x + T to world coordinates (Mantaflow: the domain's size)")
      ->check(FiniteNumber)
      ->excludes(rows);
  cmd.add_option("--translate", args.translate,
                 "T in the map x -> S x + T, as X,Y,Z (Mantaflow: the domain's centre)")
      ->expected(3)
      ->delimiter(',')
      ->check(FiniteNumber)
      ->excludes(rows);
}

namespace {

std::optional<AffineTransform> make_transform(const TransformArgs& args) {
  if (args.rows.size() == 12) return affine_from_rows(std::span<const double, 12>(args.rows));
  if (!args.scale && args.translate.empty()) return std::nullopt;
  const Vec3 translation = args.translate.size() == 3
                               ? Vec3(args.translate[0], args.translate[1], args.translate[2])
                               : Vec3::Zero();
  return scale_then_translate(args.scale.value_or(1.0), translation);
}

}  // namespace

std::optional<AffineTransform> transform_from(const TransformArgs& args) {
  try {
    return make_transform(args);
  } catch (const std::invalid_argument& e) {  // a singular or non-finite map: bad options
    throw InputError(e.what());
  }
}

}  // namespace toonwater::cli
