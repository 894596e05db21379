#include "peridot/core/resident_memory.hpp"

#include <fstream>
#include <string>

#include <sys/resource.h>

namespace peridot {

std::size_t peak_resident_bytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmHWM:", 0) == 0) return static_cast<std::size_t>(std::stoull(line.substr(6))) * 1024;  // "VmHWM:  123 kB"
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) return static_cast<std::size_t>(usage.ru_maxrss) * 1024;  // KiB on Linux
  return 0;
}

}  // namespace peridot
