// The largest single allocation a test executable made: linking largest_allocation.cpp replaces
// the global operator new (and delete) with versions that record it. Tests of hostile inputs
// use it to show that no reader allocates from a count the file does not back.
#pragma once

#include <cstddef>

namespace toonwater::test {

void reset_largest_allocation();
std::size_t largest_allocation();

}  // namespace toonwater::test
