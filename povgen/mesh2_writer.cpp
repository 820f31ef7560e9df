#include "povgen/mesh2_writer.hpp"

#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace toonwater::povgen {
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
  void number(double value) {
    if (!std::isfinite(value)) throw std::logic_error("mesh2 writer: non-finite number");
    reserve(32);
    // Round to single precision first: POV-Ray stores floats, and shortest-float formatting
    // is faster than a fixed precision; "general" with 7 digits keeps the files short.
    const auto r = std::to_chars(out_.data() + size_, out_.data() + out_.size(),
                                 static_cast<float>(value), std::chars_format::general, 7);
    size_ = static_cast<std::size_t>(r.ptr - out_.data());
  }
  void integer(std::int64_t value) {
    reserve(24);
    const auto r = std::to_chars(out_.data() + size_, out_.data() + out_.size(), value);
    size_ = static_cast<std::size_t>(r.ptr - out_.data());
  }
  void vector(const Vec3& v) {
    text("<");
    number(v.x());
    text(",");
    number(v.y());
    text(",");
    number(v.z());
    text(">");
  }

 private:
  void reserve(std::size_t n) {
    if (size_ + n > out_.size()) out_.resize(std::max(out_.size() * 3 / 2, size_ + n + 4096));
  }
  std::string& out_;
  std::size_t size_;
};

template <class Fn>
void block(Writer& w, std::string_view keyword, std::size_t count, Fn&& element) {
  w.text("  ");
  w.text(keyword);
  w.text(" { ");
  w.integer(static_cast<std::int64_t>(count));
  for (std::size_t i = 0; i < count; ++i) {
    w.text(i % 4 == 0 ? ",\n    " : ", ");
    element(i);
  }
  w.text("\n  }\n");
}

void append(std::string& out, std::string_view identifier, const SceneMesh& mesh,
            std::span<const TextureCoordinate> uv, double offset) {
  const std::size_t n = mesh.positions.size();
  Writer w(out, 256 + n * (uv.empty() ? 60 : 78) + mesh.triangles.size() * 24);
  w.text("#declare ");
  w.text(identifier);
  w.text(" = mesh2 {\n");
  block(w, "vertex_vectors", n,
        [&](std::size_t i) { w.vector(mesh.positions[i] + offset * mesh.normals[i]); });
  block(w, "normal_vectors", n, [&](std::size_t i) { w.vector(mesh.normals[i]); });
  if (!uv.empty()) {
    if (uv.size() != n) throw std::logic_error("mesh2 writer: one uv per vertex expected");
    block(w, "uv_vectors", n, [&](std::size_t i) {
      w.text("<");
      w.number(uv[i][0]);
      w.text(",");
      w.number(uv[i][1]);
      w.text(">");
    });
  }
  block(w, "face_indices", mesh.triangles.size(), [&](std::size_t i) {
    const Triangle& t = mesh.triangles[i];
    w.text("<");
    w.integer(t[0]);
    w.text(",");
    w.integer(t[1]);
    w.text(",");
    w.integer(t[2]);
    w.text(">");
  });
  // Any direction works for a closed mesh; an irrational-looking one avoids grazing edges.
  if (mesh.closed) w.text("  inside_vector <0.2718, 0.8182, 0.5069>\n");
  w.text("}\n");
}

}  // namespace

void append_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                  std::span<const TextureCoordinate> uv) {
  append(out, identifier, mesh, uv, 0.0);
}

void append_shell_mesh2(std::string& out, std::string_view identifier, const SceneMesh& mesh,
                        double offset) {
  append(out, identifier, mesh, {}, offset);
}

}  // namespace toonwater::povgen
