#include "alloycolor/core/parallel.h"

namespace alloycolor {

int ThreadBudget::Claim(int want) {
  int free = free_.load();
  while (want > 0 && free > 0) {
    const int take = std::min(want, free);
    if (free_.compare_exchange_weak(free, free - take)) return take;
  }
  return 0;
}

void ParallelTasks(std::size_t count, const std::function<void(std::size_t)>& task,
                   ThreadBudget* budget) {
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
  // Up to count - 1 helpers from the budget's free threads.
  const int want = count > 1 ? static_cast<int>(std::min<std::size_t>(count - 1, 1 << 16)) : 0;
  const int claimed = budget != nullptr ? budget->Claim(want) : 0;
  std::vector<std::thread> pool;
  pool.reserve(claimed);
  for (int t = 0; t < claimed; ++t) pool.emplace_back(work);
  work();
  for (auto& thread : pool) thread.join();
  if (budget != nullptr) budget->Return(claimed);
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace alloycolor
