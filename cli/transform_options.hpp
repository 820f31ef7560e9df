// --transform | --scale/--translate: the map from a mesh file's coordinates to world
// coordinates (Mantaflow caches: docs/inputs.md), shared by analyze and povgen.
#pragma once

#include "analyzer/affine_transform.hpp"

#include <CLI/CLI.hpp>

#include <optional>
#include <vector>

namespace toonwater::cli {

struct TransformArgs {
  std::vector<double> rows;     // 3x4 [A | b] row by row
  std::optional<double> scale;  // or x -> scale x + translate
  std::vector<double> translate;
};

void add_transform_options(CLI::App& cmd, TransformArgs& args);

// The map the options give, or nothing; throws std::invalid_argument for a singular or
// non-finite one (checked before any mesh is read).
std::optional<AffineTransform> transform_from(const TransformArgs& args);

}  // namespace toonwater::cli
