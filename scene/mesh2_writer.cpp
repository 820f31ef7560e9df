#include "scene/mesh2_writer.hpp"

#include "analyzer/free_surface.hpp"
#include "analyzer/mesh_reader.hpp"
#include "common/parallel.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <vector>

namespace toonwater {
namespace {

// Appends to a std::string through a cursor, growing it in large steps, so the hot loops do
// no per-number allocation.
class Writer {
 public:
  explicit Writer(std::string& out, std::size_t expected) : out_(out), size_(out.size()) {
    out_.resize(size_ + expected);
  }
  ~Writer() { out_.resize(size_); }

  void text(std::string_view s) {
    reserve(s.size());
    std::memcpy(out_.data() + size_, s.data(), s.size());
    size_ += s.size();
  }
  // Fixed point with `decimals` digits after the point (trailing zeros dropped): an integer
  // conversion, several times faster than floating-point formatting.
  void fixed(double value, int decimals) {
    if (!std::isfinite(value)) throw std::logic_error("mesh2 writer: non-finite number");
    reserve(48);
    const double scaled = std::round(value * kPowersOfTen[decimals]);
    if (!(std::abs(scaled) < 9e18)) throw std::logic_error("mesh2 writer: number out of range");
    auto q = static_cast<std::int64_t>(scaled);
    char* p = out_.data() + size_;
    if (q < 0) *p++ = '-', q = -q;
    const auto unit = static_cast<std::int64_t>(kPowersOfTen[decimals]);
    p = std::to_chars(p, p + 24, q / unit).ptr;
    std::int64_t fraction = q % unit;
    if (fraction != 0) {
      int digits = decimals;
      while (fraction % 10 == 0) fraction /= 10, --digits;
      *p++ = '.';
      char buf[24];
      const auto r = std::to_chars(buf, buf + sizeof buf, fraction);
      const auto len = static_cast<int>(r.ptr - buf);
      for (int z = len; z < digits; ++z) *p++ = '0';
      std::memcpy(p, buf, static_cast<std::size_t>(len));
      p += len;
    }
    size_ = static_cast<std::size_t>(p - out_.data());
  }
  static constexpr double kPowersOfTen[] = {1e0, 1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7, 1e8,
                                            1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16};
  void integer(std::int64_t value) {
    reserve(24);
    const auto r = std::to_chars(out_.data() + size_, out_.data() + out_.size(), value);
    size_ = static_cast<std::size_t>(r.ptr - out_.data());
  }
  void vector(const Vec3& v, int decimals) {
    text("<");
    fixed(v.x(), decimals);
    text(",");
    fixed(v.y(), decimals);
    text(",");
    fixed(v.z(), decimals);
    text(">");
  }

 private:
  void reserve(std::size_t n) {
    if (size_ + n > out_.size()) out_.resize(std::max(out_.size() * 3 / 2, size_ + n + 4096));
  }
  std::string& out_;
  std::size_t size_;
};

// One mesh2 block. Big blocks are formatted in contiguous chunks on all cores (each chunk into
// its own buffer), then joined in order: the text is the same as a serial pass.
template <class Fn>
void block(std::string& out, std::string_view keyword, std::size_t count,
           std::size_t bytes_per_element, Fn&& element) {
  {
    Writer w(out, 64);
    w.text("  ");
    w.text(keyword);
    w.text(" { ");
    w.integer(static_cast<std::int64_t>(count));
  }
  const std::size_t workers = chunk_count(count, 65536);
  std::vector<std::string> parts(workers);
  parallel_chunks(count, workers, [&](std::size_t chunk, std::size_t begin, std::size_t end) {
    Writer w(parts[chunk], (end - begin) * bytes_per_element);
    for (std::size_t i = begin; i < end; ++i) {
      w.text(i % 4 == 0 ? ",\n    " : ", ");
      element(w, i);
    }
  });
  for (const std::string& part : parts) out += part;
  out += "\n  }\n";
}

}  // namespace

void check_scene_extent(const SceneMesh& mesh, const std::filesystem::path& source) {
  const double largest = std::max(mesh.min.cwiseAbs().maxCoeff(), mesh.max.cwiseAbs().maxCoeff());
  if (largest < largest_scene_coordinate) return;
  char message[160];
  std::snprintf(message, sizeof message,
                ": coordinates reach %.3g; a POV-Ray scene takes them below %.0e", largest,
                largest_scene_coordinate);
  throw InputError(source.string() + message);
}

namespace {

// Unit vectors and texture coordinates: 6 decimals, finer than single precision resolves L·n.
constexpr int kUnitDecimals = 6;

// Positions get 7 significant digits relative to the mesh's largest coordinate, the precision
// POV-Ray's single-precision vertices keep.
int position_decimals(const SceneMesh& mesh, double offset) {
  const double largest =
      std::max(mesh.min.cwiseAbs().maxCoeff(), mesh.max.cwiseAbs().maxCoeff()) + std::abs(offset);
  if (!(largest > 0)) return 6;
  return std::clamp(6 - static_cast<int>(std::floor(std::log10(largest))), 0, 16);
}

// Whether face <a,b,c>'s POV-Ray normal (a−b)×(c−b) agrees with its vertex normals.
bool agrees_with_normals(const SceneMesh& mesh, const Triangle& t, Vec3* face_normal) {
  const Vec3& a = mesh.positions[t[0]];
  const Vec3& b = mesh.positions[t[1]];
  const Vec3& c = mesh.positions[t[2]];
  const Vec3 outward = (a - b).cross(c - b);
  const Vec3 mean = mesh.normals[t[0]] + mesh.normals[t[1]] + mesh.normals[t[2]];
  const bool agrees = outward.dot(mean) >= 0;
  if (face_normal) *face_normal = agrees ? outward : Vec3(-outward);
  return agrees;
}

void append(std::string& out, std::string_view identifier, const SceneMesh& mesh,
            std::span<const TextureCoordinate> uv, std::span<const double> offsets,
            std::span<const Triangle> triangles, bool closed, bool normals,
            const FaceTextures* textures, int decimals) {
  const std::size_t n = mesh.positions.size();
  if (!offsets.empty() && offsets.size() != n)
    throw std::logic_error("mesh2 writer: one offset per vertex expected");
  if (textures && textures->index.size() != triangles.size())
    throw std::logic_error("mesh2 writer: one texture index per face expected");
  if (textures && std::any_of(textures->index.begin(), textures->index.end(), [&](std::uint8_t t) {
        return t != FaceTextures::object_texture && t >= textures->names.size();
      }))
    throw std::logic_error("mesh2 writer: a face's texture is not in the list");
  out.reserve(out.size() + 256 + n * (uv.empty() ? 60 : 78) + mesh.triangles.size() * 24);
  out += "#declare ";
  out += identifier;
  out += " = mesh2 {\n";
  block(out, "vertex_vectors", n, 32, [&](Writer& w, std::size_t i) {
    w.vector(offsets.empty() ? mesh.positions[i]
                             : Vec3(mesh.positions[i] + offsets[i] * mesh.normals[i]),
             decimals);
  });
  if (normals)
    block(out, "normal_vectors", n, 32,
          [&](Writer& w, std::size_t i) { w.vector(mesh.normals[i], kUnitDecimals); });
  if (!uv.empty()) {
    if (uv.size() != n) throw std::logic_error("mesh2 writer: one uv per vertex expected");
    block(out, "uv_vectors", n, 20, [&](Writer& w, std::size_t i) {
      w.text("<");
      w.fixed(uv[i][0], kUnitDecimals);
      w.text(",");
      w.fixed(uv[i][1], kUnitDecimals);
      w.text(">");
    });
  }
  if (textures) {
    out += "  texture_list { " + std::to_string(textures->names.size());
    for (const std::string& name : textures->names) out += ", texture { " + name + " }";
    out += " }\n";
  }
  block(out, "face_indices", triangles.size(), 28, [&](Writer& w, std::size_t i) {
    const Triangle& t = triangles[i];
    w.text("<");
    w.integer(t[0]);
    w.text(",");
    w.integer(t[1]);
    w.text(",");
    w.integer(t[2]);
    w.text(">");
    if (textures && textures->index[i] != FaceTextures::object_texture) {
      w.text(",");
      w.integer(textures->index[i]);
    }
  });
  // Any direction works for a closed mesh; an irrational-looking one avoids grazing edges.
  if (closed) out += "  inside_vector <0.2718, 0.8182, 0.5069>\n";
  out += "}\n";
}

}  // namespace

void append_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                  std::span<const TextureCoordinate> uv, const FaceTextures* textures) {
  append(out, identifier, mesh, uv, {}, mesh.triangles, mesh.closed, /*normals=*/true, textures,
         position_decimals(mesh, 0.0));
}

std::vector<bool> upward_faces(const SceneMesh& mesh) {
  std::vector<bool> up(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    Vec3 normal;
    agrees_with_normals(mesh, mesh.triangles[f], &normal);
    up[f] = normal.y() > shell_min_up_component * normal.norm();
  }
  return up;
}

Triangle shell_winding(const SceneMesh& mesh, const Triangle& t) {
  return agrees_with_normals(mesh, t, nullptr) ? t : Triangle{t[0], t[2], t[1]};
}

void append_shell_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                        std::span<const double> offsets, const std::vector<bool>* keep) {
  if (offsets.size() != mesh.positions.size())
    throw std::logic_error("mesh2 writer: one offset per vertex expected");
  // The precision of the whole shell, also when only some faces are written: the positions
  // POV-Ray reads do not depend on which faces are left out.
  const int decimals = position_decimals(
      mesh, offsets.empty() ? 0.0 : *std::max_element(offsets.begin(), offsets.end()));
  // The shell is drawn flat, so it needs no normals; without them POV-Ray takes (a−b)×(c−b) of
  // face <a,b,c> as the outward side. Each face is wound to agree with its vertex normals,
  // which also drops a third of the shell's text and parse time.
  if (!keep) {
    std::vector<Triangle> oriented;
    oriented.reserve(mesh.triangles.size());
    for (const Triangle& t : mesh.triangles) oriented.push_back(shell_winding(mesh, t));
    append(out, identifier, mesh, {}, offsets, oriented, mesh.closed, /*normals=*/false, nullptr,
           decimals);
    return;
  }
  // Only the marked faces, and only the vertices they use (vertices are a fifth of a shell's
  // parse time), renumbered in their order.
  SceneMesh part;
  part.min = mesh.min;
  part.max = mesh.max;
  std::vector<double> part_offsets;
  std::vector<int> index(mesh.positions.size(), -1);
  std::vector<Triangle> oriented;
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    if (!(*keep)[f]) continue;
    Triangle t = shell_winding(mesh, mesh.triangles[f]);
    for (int& v : t) {
      if (index[v] < 0) {
        index[v] = static_cast<int>(part.positions.size());
        part.positions.push_back(mesh.positions[v]);
        part.normals.push_back(mesh.normals[v]);
        part_offsets.push_back(offsets[v]);
      }
      v = index[v];
    }
    oriented.push_back(t);
  }
  if (oriented.empty()) {  // POV-Ray rejects a mesh2 without faces
    out += "#declare ";
    out += identifier;
    out += " = union {}\n";
    return;
  }
  append(out, identifier, part, {}, part_offsets, oriented, /*closed=*/false, /*normals=*/false,
         nullptr, decimals);
}

}  // namespace toonwater
