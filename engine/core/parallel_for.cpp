#include "core/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace planet {

void parallelFor(size_t count, size_t chunkSize, unsigned threads, const std::function<void(size_t, size_t)>& work,
                 const ProgressCallback& progress) {
  chunkSize = std::max<size_t>(chunkSize, 1);
  const size_t chunks = (count + chunkSize - 1) / chunkSize;
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  threads = unsigned(std::min<size_t>(threads, std::max<size_t>(chunks, 1)));

  std::atomic<size_t> nextChunk{0};
  std::atomic<size_t> done{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::condition_variable finished;
  unsigned running = threads;
  std::exception_ptr error;

  auto worker = [&] {
    try {
      for (size_t chunk; !failed.load() && (chunk = nextChunk.fetch_add(1)) < chunks;) {
        const size_t begin = chunk * chunkSize;
        const size_t end = std::min(count, begin + chunkSize);
        work(begin, end);
        done.fetch_add(end - begin);
      }
    } catch (...) {
      std::lock_guard lock(mutex);
      if (!error) error = std::current_exception();
      failed.store(true);
    }
    std::lock_guard lock(mutex);
    if (--running == 0) finished.notify_one();
  };

  std::vector<std::thread> pool;
  pool.reserve(threads);
  for (unsigned t = 0; t < threads; ++t) pool.emplace_back(worker);
  {
    std::unique_lock lock(mutex);
    while (!finished.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) {
      if (!progress || failed.load()) continue;
      lock.unlock();
      try {
        progress(done.load(), count);
      } catch (...) {
        // The workers must still be joined: stop them and rethrow below.
        std::lock_guard errorLock(mutex);
        if (!error) error = std::current_exception();
        failed.store(true);
      }
      lock.lock();
    }
  }
  for (std::thread& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
  if (progress) progress(count, count);
}

}  // namespace planet
