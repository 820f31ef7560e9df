// Curvature as data, one row per input vertex in input order:
//   CSV  header "x,y,z,gaussian,mean,k1,k2,area,label,flow", shortest round-trip decimal
//        numbers (label: 1 ridge, −1 valley, 0 none; flow: the signed flow field s of
//        flow_regions.hpp, a region where |s| >= 1);
//   PLY  binary little-endian, the input mesh with float vertex properties of the same names
//        (MeshLab and ParaView colour by them).
// Both are written atomically (atomic_file.hpp) in blocks, so memory does not grow with the
// file, and never contain NaN or Inf.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"

#include <filesystem>
#include <vector>

namespace toonwater {

// CSV rows per input vertex; the positions are the surface's (welding merged only vertices at
// exactly the same position, so they are the input's, bit for bit).
void write_curvature_csv(const std::filesystem::path& path, const Analysis& analysis);

// Binary PLY of the input mesh: `input_triangles` index input vertices, as read.
void write_curvature_ply(const std::filesystem::path& path,
                         const std::vector<Triangle>& input_triangles, const Analysis& analysis);

}  // namespace toonwater
