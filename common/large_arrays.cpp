#include "common/large_arrays.hpp"

#include <malloc.h>

namespace toonwater {

void keep_large_arrays_in_the_heap() {
  constexpr int largest_kept = 1 << 30;  // bytes; larger arrays are still mapped alone
  mallopt(M_MMAP_THRESHOLD, largest_kept);
  mallopt(M_TRIM_THRESHOLD, largest_kept);
}

}  // namespace toonwater
