#include "core/process_memory.h"

#include <unistd.h>

#include <cstdio>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace planet {

int64_t residentKiB() {
  FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  long pages = 0, resident = 0;
  const int read = std::fscanf(f, "%ld %ld", &pages, &resident);
  std::fclose(f);
  const long pageKiB = sysconf(_SC_PAGESIZE) / 1024;
  return read == 2 && pageKiB > 0 ? int64_t(resident) * pageKiB : 0;
}

void keepLargeBlocksOutOfTheHeap() {
#if defined(__GLIBC__)
  // Setting the threshold explicitly also turns off glibc's dynamic raising of it (mallopt(3)).
  mallopt(M_MMAP_THRESHOLD, kLargeBlockBytes);
#endif
}

}  // namespace planet
