// A frame's record in the frame cache, field by field (see frame_record.hpp).
#include "pipeline/frame_record.hpp"

namespace toonwater {
namespace {

template <class Record, class Mesh, class Curvature, class Labels, class FreeSurface>
void map_input_fields(Record& record, Mesh& surface, Curvature& curvature, Labels& label,
                      FreeSurface& free_surface) {
  mesh_fields(record, surface);
  record.field(curvature.gaussian);
  record.field(curvature.mean);
  record.field(label);
  record.field(free_surface);
}

// Packs or reads back one field of a prepared surface: a struct with a field list of its own
// field by field, a vector of such structs as its size and then each element's fields.
template <class Record>
struct SurfaceField {
  Record& record;
  template <class T>
  void operator()(T& value) const {
    using Plain = std::remove_const_t<T>;
    if constexpr (std::is_same_v<Plain, SceneMesh>) {
      for_each_field(value, *this);
    } else if constexpr (std::is_same_v<Plain, std::vector<FlowLine>>) {
      record.count(value);
      for (auto& line : value) for_each_field(line, *this);
    } else {
      record.field(value);
    }
  }
};

}  // namespace

void pack_map_inputs(RecordWriter& out, const Analysis& a) {
  map_input_fields(out, a.surface, a.curvature, a.flow.label, a.flow.free_surface);
}

MapInputs unpack_map_inputs(RecordReader& in) {
  MapInputs m;
  map_input_fields(in, m.surface, m.curvature, m.label, m.free_surface);
  return m;
}

void pack_surface(RecordWriter& out, const PreparedSurface& s) {
  for_each_field(s, SurfaceField<RecordWriter>{out});
}

PreparedSurface unpack_surface(RecordReader& in) {
  PreparedSurface s;
  for_each_field(s, SurfaceField<RecordReader>{in});
  return s;
}

}  // namespace toonwater
