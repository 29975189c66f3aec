// The process's own memory as the kernel counts it: what a soak or leak check compares (the
// viewer's memory line, planet bench soak). Device memory the allocator holds is counted by
// vk::Allocator::stats(); on a CPU device (lavapipe) it is part of this figure too.
#pragma once

#include <cstdint>

namespace planet {

// Resident set size in KiB (/proc/self/statm, second field, times the page size); 0 where it
// cannot be read (not Linux).
int64_t residentKiB();

// Blocks of at least this size get a mapping of their own from glibc's malloc once
// keepLargeBlocksOutOfTheHeap() ran, and go back to the system when freed.
inline constexpr int kLargeBlockBytes = 1 << 20;

// Pins glibc's mmap threshold at kLargeBlockBytes (does nothing with another C library). By
// default glibc raises the threshold to the largest mapped block freed so far, up to 32 MiB; the
// driver's shader compiles (lavapipe: LLVM) free blocks of several MiB, so afterwards such blocks
// come from the heap, which those compiles left fragmented, and it grows for good: a Renderer
// rebuild and the first wireframe frames added 5-10 MiB of resident memory (docs/benchmarks.md,
// "Shader compiles and resident memory"), 2-5 MiB with the threshold pinned. A process calls it
// once, first thing (planet's main does).
void keepLargeBlocksOutOfTheHeap();

}  // namespace planet
