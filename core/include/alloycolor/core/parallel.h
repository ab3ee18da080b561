// Splitting work over threads: the renderer's rows and tables over a number of threads it
// is given (ParallelFor), and the folds of fits and validations over the machine's cores
// (ParallelTasks), sharing them when such work nests.
#ifndef ALLOYCOLOR_CORE_PARALLEL_H_
#define ALLOYCOLOR_CORE_PARALLEL_H_

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace alloycolor {

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

// The threads one piece of work may use in all (the caller's included; 0: every core of
// the machine), shared by the ParallelTasks calls it makes, nested ones too. The face that
// starts the work owns it and hands it in (FitSettings::threads, ValidationOptions).
class ThreadBudget {
 public:
  explicit ThreadBudget(int threads = 0) : free_(ThreadCount(threads) - 1) {}
  ThreadBudget(const ThreadBudget&) = delete;
  ThreadBudget& operator=(const ThreadBudget&) = delete;
  // Up to `want` threads beyond the caller's, as many as are free; Return gives them back.
  int Claim(int want);
  void Return(int threads) { free_ += threads; }

 private:
  std::atomic<int> free_;
};

// Calls task(i) for every i in [0, count), on the calling thread and the budget's threads
// not already running such tasks (a call made inside a task gets the threads still free,
// often none, and then runs its tasks in turn on its own thread; no budget: all in turn on
// the caller's). Every task runs; then the exception of the lowest i, if any, is rethrown,
// so the outcome does not depend on the timing. The tasks must not share mutable state
// (each writes its own result).
void ParallelTasks(std::size_t count, const std::function<void(std::size_t)>& task,
                   ThreadBudget* budget);

}  // namespace alloycolor

#endif  // ALLOYCOLOR_CORE_PARALLEL_H_
