// parallelFor (core/parallel_for.h): every index once, progress on the calling thread ending at
// the total, and a worker's exception rethrown after all have stopped.
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "core/parallel_for.h"

namespace planet {
namespace {

TEST(ParallelFor, CoversEveryIndexOnceInChunksOfAtMostTheChunkSize) {
  for (unsigned threads : {0u, 1u, 3u, 16u}) {
    for (size_t count : {size_t(0), size_t(1), size_t(7), size_t(1000)}) {
      SCOPED_TRACE(std::to_string(threads) + " threads, " + std::to_string(count) + " items");
      std::vector<std::atomic<int>> visits(count);
      std::atomic<bool> chunkTooLarge{false};
      parallelFor(count, 3, threads, [&](size_t begin, size_t end) {
        if (end - begin > 3 || end <= begin) chunkTooLarge = true;
        for (size_t i = begin; i < end; ++i) visits[i].fetch_add(1);
      });
      EXPECT_FALSE(chunkTooLarge);
      for (size_t i = 0; i < count; ++i) ASSERT_EQ(visits[i].load(), 1) << i;
    }
  }
}

TEST(ParallelFor, ReportsProgressOnTheCallingThreadEndingWithTheTotal) {
  const std::thread::id caller = std::this_thread::get_id();
  std::vector<size_t> reports;
  bool otherThread = false;
  parallelFor(
      40, 1, 2, [](size_t, size_t) { std::this_thread::sleep_for(std::chrono::milliseconds(10)); },
      [&](size_t done, size_t total) {
        otherThread = otherThread || std::this_thread::get_id() != caller;
        EXPECT_EQ(total, 40u);
        reports.push_back(done);
      });
  EXPECT_FALSE(otherThread);
  // About 200 ms of work: a report every ~100 ms, non-decreasing, the last one the total.
  ASSERT_GE(reports.size(), 2u);
  for (size_t i = 1; i < reports.size(); ++i) EXPECT_LE(reports[i - 1], reports[i]);
  EXPECT_EQ(reports.back(), 40u);
}

TEST(ParallelFor, RethrowsAWorkersExceptionAndStopsTakingChunks) {
  std::atomic<size_t> chunksRun{0};
  bool finalReport = false;
  // Every other chunk takes a little time: empty chunks let the other workers run all 100,000
  // while the throwing one was still unwinding (seen under ASan in CI); at >= 20 µs each they
  // would need over half a second, so a stop that works shows as far fewer.
  EXPECT_THROW(parallelFor(
                   100000, 1, 4,
                   [&](size_t begin, size_t) {
                     chunksRun.fetch_add(1);
                     if (begin == 10) throw std::runtime_error("chunk 10");
                     std::this_thread::sleep_for(std::chrono::microseconds(20));
                   },
                   [&](size_t done, size_t total) { finalReport = finalReport || done == total; }),
               std::runtime_error);
  EXPECT_LT(chunksRun.load(), 50000u);
  EXPECT_FALSE(finalReport);
}

}  // namespace
}  // namespace planet
