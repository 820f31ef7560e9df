// Where glibc keeps arrays of tens of megabytes: in the heap, for the whole process, on huge
// pages where the kernel offers them.
//
// An analysis allocates and frees such arrays in turn (a 1M-vertex frame: positions, faces,
// one-rings, curvature, flow), and povgen does it again for every frame. By default glibc maps
// each array of 32 MB or more afresh and unmaps it when freed, so every one pays again for page
// faults and for the kernel's zeroing of its pages: a quarter of the CPU time of a 1M-vertex
// analysis. Kept in the heap instead, a freed array's pages serve the next ones; the peak stays
// what it was, since the heap only holds what was once in use at the same time.
//
// The first touch of each 4 KB page still faults: 45,000 times in a 1M-vertex analysis, a
// third of its CPU time on a virtual machine. The heap's first `huge_page_heap_bytes` are
// therefore advised for transparent huge pages (madvise(MADV_HUGEPAGE), which a kernel whose
// THP mode is `madvise`, Debian's default, needs before it maps 2 MB at a fault): that analysis
// then faults 4,700 times, and its CPU time falls by a third (docs/performance.md, "Analyzer
// against MeshLab"). This is what glibc's own `glibc.malloc.hugetlb=1` does, which is read only
// from the environment as a process starts. The advice reserves no memory: a huge page is mapped
// only where the heap is touched, so a process holds at most about 2 MB more than it touched, at
// the heap's top (the 1M analysis's peak: 2 MB more).
#pragma once

#include <cstddef>

namespace toonwater {

// The length of the heap, from its start, advised for huge pages: a 1M-vertex povgen frame
// (520 B a vertex at its peak) fits.
inline constexpr std::size_t huge_page_heap_bytes = std::size_t{1} << 29;

// Call once, early in main, before the large arrays are allocated. Where the advice cannot be
// given (the allocation or madvise fails, or the allocator is not glibc's), the arrays are
// still kept in the heap, on ordinary pages.
void set_up_heap_for_large_arrays();

}  // namespace toonwater
