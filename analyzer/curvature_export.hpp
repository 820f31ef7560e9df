// Curvature as data, one row per input vertex in input order:
//   CSV  header "x,y,z,gaussian,mean,k1,k2,area,label", shortest round-trip decimal numbers;
//   PLY  binary little-endian, the input mesh with float vertex properties of the same names
//        (MeshLab and ParaView colour by them).
// Both are written atomically (atomic_file.hpp) and never contain NaN or Inf.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"

#include <filesystem>
#include <string>

namespace toonwater {

std::string curvature_csv(const TriangleMesh& input, const Analysis& analysis);
std::string curvature_ply(const TriangleMesh& input, const Analysis& analysis);

void write_curvature_csv(const std::filesystem::path& path, const TriangleMesh& input,
                         const Analysis& analysis);
void write_curvature_ply(const std::filesystem::path& path, const TriangleMesh& input,
                         const Analysis& analysis);

}  // namespace toonwater
