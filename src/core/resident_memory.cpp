#include "iarap/core/resident_memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

namespace iarap {

std::size_t peak_resident_bytes() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<std::size_t>(usage.ru_maxrss) * 1024; // kilobytes on Linux
}

std::size_t current_resident_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return 0;
  return resident * static_cast<std::size_t>(sysconf(_SC_PAGESIZE));
}

} // namespace iarap
