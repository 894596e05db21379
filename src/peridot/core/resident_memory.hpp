#pragma once
// What the operating system says this process holds in memory: the measure the memory budget of a
// distributed run is stated in (docs/parallel.md), beside the estimate of the points and bonds alone.
#include <cstddef>

namespace peridot {

/// Peak resident set size of this process so far (bytes): Linux's VmHWM, else getrusage's ru_maxrss; 0 when
/// neither is available.
std::size_t peak_resident_bytes();

}  // namespace peridot
