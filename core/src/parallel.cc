#include "alloycolor/core/parallel.h"

namespace alloycolor {
namespace {

// Threads beyond the callers' own that ParallelTasks may start, over the whole process.
std::atomic<int>& FreeThreads() {
  static std::atomic<int> free{ThreadCount(0) - 1};
  return free;
}

}  // namespace

void SetParallelTaskThreads(int threads) { FreeThreads() = ThreadCount(threads) - 1; }

void ParallelTasks(std::size_t count, const std::function<void(std::size_t)>& task) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  const auto work = [&]() {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        task(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  // Claim up to count - 1 helpers from the free threads.
  int claimed = 0;
  int free = FreeThreads().load();
  const int want = count > 1 ? static_cast<int>(std::min<std::size_t>(count - 1, 1 << 16)) : 0;
  while (want > 0 && free > 0) {
    const int take = std::min(want, free);
    if (FreeThreads().compare_exchange_weak(free, free - take)) {
      claimed = take;
      break;
    }
  }
  std::vector<std::thread> pool;
  pool.reserve(claimed);
  for (int t = 0; t < claimed; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  FreeThreads() += claimed;
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace alloycolor
