// A loop over [0, count) on several threads with progress reported on the calling thread, for
// long CPU work a user waits for (planet export).
#pragma once

#include <cstddef>
#include <functional>

namespace planet {

// progress(done, total): `done` of `total` items are finished.
using ProgressCallback = std::function<void(size_t done, size_t total)>;

// Calls work(begin, end) on disjoint chunks of at most `chunkSize` items that together cover
// [0, count) exactly once, taken in order from a shared counter by `threads` worker threads
// (0: one per hardware thread). The calling thread only waits: it calls `progress` about every
// 100 ms and once at the end with done == total (after every chunk finished), so a callback may
// print without locking. The first exception a chunk throws stops the workers from taking new
// chunks and is rethrown here once all have stopped (no final progress call then); so is one that
// `progress` throws.
void parallelFor(size_t count, size_t chunkSize, unsigned threads, const std::function<void(size_t, size_t)>& work,
                 const ProgressCallback& progress = {});

}  // namespace planet
