// A sequence's frames kept between the pass that reads and analyses them and the pass that
// writes them, for a scene whose frames share something only the whole sequence gives (the
// default camera's box, a curvature view's colour range, the curvature maps' view and ranges):
// each frame is then read and analysed once, not once for that survey and again to be written.
//
// A record is a frame's bytes (frame_record.hpp packs what its writing needs). Records stay in
// memory while their total stays within `memory_budget` bytes; beyond it, a record goes to one
// temporary binary file (appended, read back by offset), so hundreds of large frames never sit
// in memory together. The file is removed when the cache is destroyed; it lives in the scene's
// staging directory, which a failed run removes whole (scene_directory.hpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace toonwater {

template <class T>
constexpr bool is_vector = false;
template <class T, class A>
constexpr bool is_vector<std::vector<T, A>> = true;

class FrameCache {
 public:
  FrameCache(std::filesystem::path spill_file, std::size_t memory_budget);
  ~FrameCache();
  FrameCache(const FrameCache&) = delete;
  FrameCache& operator=(const FrameCache&) = delete;

  // Appends a copy of the next record. Throws OutputError when the spill file cannot be written.
  void put(std::string_view record);
  // Record i, once, into `record` (whose memory is reused: a loop passes the same string);
  // a record in memory gives its memory back. Throws OutputError.
  void take(std::size_t i, std::string& record);
  std::size_t size() const { return entries_.size(); }
  std::size_t spilled() const { return spilled_; }  // records written to the file

 private:
  struct Entry {
    std::string bytes;  // in memory
    bool on_disk = false;
    std::uint64_t offset = 0, size = 0;
  };
  std::filesystem::path path_;
  std::size_t budget_, in_memory_ = 0, spilled_ = 0;
  std::uint64_t file_size_ = 0;
  std::FILE* file_ = nullptr;
  std::vector<Entry> entries_;
};

// Plain values (numbers, fixed-size Eigen vectors, index triples: no pointers) and vectors of
// them packed into a record by their bytes, and read back in the same order.
//
// Both classes also take `field(x)`, which packs x or reads it back into x by its type, and
// `count(v)`, which packs v's size or resizes v to it: a record's layout is then written once,
// as one function template over the two (frame_record.hpp), and packing and reading cannot
// drift.
class RecordWriter {
 public:
  template <class T>
  void field(const T& v) {
    if constexpr (std::is_same_v<T, std::string>)
      string(v);
    else if constexpr (is_vector<T>)
      vector(v);
    else
      value(v);
  }
  template <class T>
  void count(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
  }
  template <class T>
  void value(const T& v) {
    bytes_.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  template <class T>
  void vector(const std::vector<T>& v) {
    value<std::uint64_t>(v.size());
    bytes_.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(T));
  }
  void string(const std::string& s) {
    value<std::uint64_t>(s.size());
    bytes_.append(s);
  }
  // The record so far; clear() starts the next one in the same memory.
  std::string_view bytes() const { return bytes_; }
  void clear() { bytes_.clear(); }

 private:
  std::string bytes_;
};

class RecordReader {
 public:
  explicit RecordReader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  void field(T& v) {
    if constexpr (std::is_same_v<T, std::string>)
      v = string();
    else if constexpr (is_vector<T>)
      v = vector<typename T::value_type>();
    else
      v = value<T>();
  }
  template <class T>
  void count(std::vector<T>& v) {
    v.resize(value<std::uint64_t>());
  }
  template <class T>
  T value() {
    T v;
    std::memcpy(static_cast<void*>(&v), next(sizeof v), sizeof v);
    return v;
  }
  template <class T>
  std::vector<T> vector() {
    const auto n = value<std::uint64_t>();
    const char* from = next(n * sizeof(T));
    std::vector<T> v(n);
    // An empty vector's data() may be null, which memcpy must not be given even for 0 bytes.
    if (n > 0) std::memcpy(reinterpret_cast<char*>(v.data()), from, n * sizeof(T));
    return v;
  }
  std::string string() {
    const auto n = value<std::uint64_t>();
    return std::string(next(n), n);
  }

 private:
  const char* next(std::size_t n) {
    if (n > bytes_.size() - at_) throw std::logic_error("frame cache: record read past its end");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  const std::string& bytes_;
  std::size_t at_ = 0;
};

}  // namespace toonwater
