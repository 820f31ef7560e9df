// large_arrays.hpp: after set-up, an array of tens of megabytes lies in the heap (so its pages
// serve the next array once it is freed) and in a range advised for transparent huge pages, as
// the process's own memory map (/proc/self/smaps) shows.
#include "common/large_arrays.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

namespace toonwater {
namespace {

struct Mapping {
  std::string name;      // "[heap]", a file, or empty for anonymous memory
  std::string vm_flags;  // two-letter flags; "hg": advised for huge pages
};

// The mapping of /proc/self/smaps that holds `address`.
std::optional<Mapping> mapping_of(const void* address) {
  const auto target = reinterpret_cast<std::uintptr_t>(address);
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  std::optional<Mapping> found;
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::istringstream fields(line);
    std::string first;
    fields >> first;
    const auto dash = first.find('-');
    if (dash != std::string::npos && first.find(':') == std::string::npos) {
      // A mapping's first line: "begin-end perms offset dev inode [name]".
      if (found) return found;
      const std::uintptr_t begin = std::stoull(first.substr(0, dash), nullptr, 16);
      const std::uintptr_t end = std::stoull(first.substr(dash + 1), nullptr, 16);
      inside = begin <= target && target < end;
      if (inside) {
        std::string perms, offset, device, inode, name;
        fields >> perms >> offset >> device >> inode >> name;
        found = Mapping{name, ""};
      }
    } else if (inside && first == "VmFlags:") {
      std::getline(fields, found->vm_flags);
    }
  }
  return found;
}

bool has_flag(const std::string& vm_flags, const std::string& flag) {
  std::istringstream flags(vm_flags);
  std::string each;
  while (flags >> each)
    if (each == flag) return true;
  return false;
}

TEST(LargeArrays, ArraysOfTensOfMegabytesLieInTheHeapOnPagesAdvisedForHugePages) {
  set_up_heap_for_large_arrays();
  constexpr std::size_t bytes = std::size_t{64} << 20;  // above glibc's default 32 MB ceiling
  for (int array = 0; array < 2; ++array) {
    const auto block =
        std::make_unique_for_overwrite<char[]>(bytes);  // untouched: the map holds it
    for (const char* inside : {block.get(), block.get() + bytes - 1}) {
      const std::optional<Mapping> mapping = mapping_of(inside);
      ASSERT_TRUE(mapping) << "no mapping holds the array";
      EXPECT_EQ(mapping->name, "[heap]") << "array " << array << " is mapped on its own";
      EXPECT_TRUE(has_flag(mapping->vm_flags, "hg"))
          << "array " << array
          << " lies in a range not advised for huge pages (VmFlags:" << mapping->vm_flags << ")";
    }
  }
}

}  // namespace
}  // namespace toonwater
