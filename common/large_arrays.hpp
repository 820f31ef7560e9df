// Where glibc keeps arrays of tens of megabytes: in the heap, for the whole process.
//
// An analysis allocates and frees such arrays in turn (a 1M-vertex frame: positions, faces,
// one-rings, curvature, flow), and povgen does it again for every frame. By default glibc maps
// each array of 32 MB or more afresh and unmaps it when freed, so every one pays again for page
// faults and for the kernel's zeroing of its pages: a quarter of the CPU time of a 1M-vertex
// analysis. Kept in the heap instead, a freed array's pages serve the next ones; the peak stays
// what it was, since the heap only holds what was once in use at the same time.
#pragma once

namespace toonwater {

// Call once, early in main, before the large arrays are allocated.
void keep_large_arrays_in_the_heap();

}  // namespace toonwater
