#include "analyzer/obj_writer.hpp"

#include "common/atomic_file.hpp"

#include <charconv>
#include <stdexcept>

namespace toonwater {

std::string obj_text(const TriangleMesh& mesh, std::string_view comment) {
  std::string out;
  out.reserve(64 * mesh.positions.size() + 32 * mesh.triangles.size() + comment.size() + 4);
  if (!comment.empty()) {
    out += "# ";
    out += comment;
    out += '\n';
  }
  char buf[32];
  auto put_index = [&](std::int32_t index) {
    const auto r = std::to_chars(buf, buf + sizeof buf, index);
    out.append(buf, r.ptr);
  };
  auto put_coordinate = [&](double value) {
    const auto r = std::to_chars(buf, buf + sizeof buf, value);  // shortest round trip
    out.append(buf, r.ptr);
  };
  for (const Vec3& p : mesh.positions) {
    if (!p.allFinite()) throw std::invalid_argument("OBJ writer: a vertex is NaN or infinite");
    out += 'v';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      put_coordinate(p[k]);
    }
    out += '\n';
  }
  for (const Triangle& t : mesh.triangles) {
    out += 'f';
    for (int k = 0; k < 3; ++k) {
      out += ' ';
      put_index(t[static_cast<std::size_t>(k)] + 1);
    }
    out += '\n';
  }
  return out;
}

void write_obj(const std::filesystem::path& path, const TriangleMesh& mesh,
               std::string_view comment) {
  write_file_atomically(path, obj_text(mesh, comment));
}

}  // namespace toonwater
