#include "common/large_arrays.hpp"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace toonwater {

void set_up_heap_for_large_arrays() {
  constexpr int largest_kept = 1 << 30;  // bytes; larger arrays are still mapped alone
  static_assert(huge_page_heap_bytes < largest_kept);
  mallopt(M_MMAP_THRESHOLD, largest_kept);
  mallopt(M_TRIM_THRESHOLD, largest_kept);
  // Grows the heap by that much and gives it back to the heap's free top at once: below both
  // thresholds, the range stays the heap's, untouched, and the advice stays with its pages for
  // whichever arrays come to lie there.
  void* const block = std::malloc(huge_page_heap_bytes);
  if (block == nullptr) return;
  // madvise takes whole pages: from the page the block starts in, which it may share with
  // smaller allocations (the advice changes how pages are mapped, not what they hold).
  const auto begin = reinterpret_cast<std::uintptr_t>(block);
  const auto page_bytes = static_cast<std::uintptr_t>(sysconf(_SC_PAGESIZE));
  const std::uintptr_t first = begin & ~(page_bytes - 1);
  madvise(reinterpret_cast<void*>(first), begin + huge_page_heap_bytes - first,
          MADV_HUGEPAGE);  // advice: may fail, and nothing depends on it
  std::free(block);
}

}  // namespace toonwater
