// Records in memory within a budget, the rest in one temporary file (see frame_cache.hpp).
#include "pipeline/frame_cache.hpp"

#include "common/atomic_file.hpp"

#include <cerrno>
#include <system_error>

namespace toonwater {
namespace {

std::string error_text() { return std::generic_category().message(errno); }

}  // namespace

FrameCache::FrameCache(std::filesystem::path spill_file, std::size_t memory_budget)
    : path_(std::move(spill_file)), budget_(memory_budget) {}

FrameCache::~FrameCache() {
  if (!file_) return;
  std::fclose(file_);
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

void FrameCache::put(std::string_view record) {
  Entry e;
  e.size = record.size();
  if (in_memory_ + record.size() <= budget_) {
    in_memory_ += record.size();
    e.bytes = record;
    entries_.push_back(std::move(e));
    return;
  }
  if (!file_) {
    file_ = std::fopen(path_.c_str(), "w+b");
    if (!file_) throw OutputError("cannot create " + path_.string() + ": " + error_text());
  }
  if (fseeko(file_, 0, SEEK_END) != 0 ||
      std::fwrite(record.data(), 1, record.size(), file_) != record.size())
    throw OutputError("cannot write " + path_.string() + ": " + error_text());
  e.on_disk = true;
  e.offset = file_size_;
  file_size_ += record.size();
  ++spilled_;
  entries_.push_back(std::move(e));
}

void FrameCache::take(std::size_t i, std::string& record) {
  Entry& e = entries_.at(i);
  if (!e.on_disk) {
    in_memory_ -= e.bytes.size();
    record = std::move(e.bytes);
    e.bytes = std::string();
    return;
  }
  record.resize(e.size);
  if (std::fflush(file_) != 0 || fseeko(file_, static_cast<off_t>(e.offset), SEEK_SET) != 0 ||
      std::fread(record.data(), 1, record.size(), file_) != record.size())
    throw OutputError("cannot read " + path_.string() + ": " + error_text());
}

}  // namespace toonwater
