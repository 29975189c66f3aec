// The process's own memory as the kernel counts it: what a soak or leak check compares (the
// viewer's memory line, planet bench soak). Device memory the allocator holds is counted by
// vk::Allocator::stats(); on a CPU device (lavapipe) it is part of this figure too.
#pragma once

#include <cstdint>

namespace planet {

// Resident set size in KiB (/proc/self/statm, second field, times the page size); 0 where it
// cannot be read (not Linux).
int64_t residentKiB();

}  // namespace planet
