// A frame's record in the frame cache (frame_cache.hpp): why it has no water ("" when it has),
// then, with water, its map inputs (when the scene has maps) and its prepared surface; then,
// where the survey read them (for the camera's box), the frame's animated objects' meshes.
//
// Each part's fields are listed once, for packing (Record = RecordWriter, const fields) and
// reading back (RecordReader): a prepared surface through its one field list
// (for_each_field, prepared_surface.hpp), so no field of it can be left out of the record.
#pragma once

#include "analyzer/analysis.hpp"
#include "analyzer/mesh.hpp"
#include "pipeline/frame_cache.hpp"
#include "scene/prepared_surface.hpp"

#include <cstdint>
#include <type_traits>
#include <vector>

namespace toonwater {

// What the maps of a frame are drawn from (rasterize_top_down): its surface, curvature, labels
// and free surface.
struct MapInputs {
  TriangleMesh surface;
  CurvatureField curvature;  // gaussian, mean
  std::vector<std::int8_t> label;
  std::vector<std::uint8_t> free_surface;
};

template <class Record, class Mesh>
void mesh_fields(Record& record, Mesh& mesh) {
  record.field(mesh.positions);
  record.field(mesh.triangles);
}

void pack_map_inputs(RecordWriter& out, const Analysis& a);
MapInputs unpack_map_inputs(RecordReader& in);

void pack_surface(RecordWriter& out, const PreparedSurface& s);
PreparedSurface unpack_surface(RecordReader& in);

}  // namespace toonwater
