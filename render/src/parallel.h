// Splitting work over threads (internal to the render library).
#ifndef ALLOYCOLOR_RENDER_SRC_PARALLEL_H_
#define ALLOYCOLOR_RENDER_SRC_PARALLEL_H_

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace alloycolor::render::internal {

// How many threads to use for a request of `threads` (0: the hardware's count).
inline int ThreadCount(int threads) {
  if (threads > 0) return threads;
  const unsigned hardware = std::thread::hardware_concurrency();
  return hardware > 0 ? static_cast<int>(hardware) : 1;
}

// Calls body(begin, end) on consecutive blocks of [0, count) of `block` items, from
// `threads` threads taking blocks in turn; the first exception thrown is rethrown.
template <typename Body>
void ParallelFor(int count, int block, int threads, const Body& body) {
  block = std::max(block, 1);
  const int blocks = (count + block - 1) / block;
  threads = std::max(1, std::min(threads, blocks));
  if (threads == 1) {
    for (int b = 0; b < blocks; ++b) body(b * block, std::min(count, (b + 1) * block));
    return;
  }
  std::atomic<int> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  const auto work = [&]() {
    try {
      for (int b = next++; b < blocks; b = next++) {
        body(b * block, std::min(count, (b + 1) * block));
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = blocks;
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace alloycolor::render::internal

#endif  // ALLOYCOLOR_RENDER_SRC_PARALLEL_H_
