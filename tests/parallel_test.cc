// ParallelTasks (core/parallel.h): every task runs once, nested calls share one budget of
// threads and still run everything, the budget's threads come back, no budget runs all on
// the caller's thread, and the outcome does not depend on the timing: the exception of the
// lowest index is the one rethrown.
#include "alloycolor/core/parallel.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace alloycolor {
namespace {

TEST(ParallelTasks, RunsEveryTaskOnce) {
  for (size_t count : {0, 1, 2, 3, 17, 1000}) {
    std::vector<int> runs(count, 0);
    ThreadBudget budget(4);
    ParallelTasks(
        count, [&](size_t i) { ++runs[i]; }, &budget);
    for (size_t i = 0; i < count; ++i) EXPECT_EQ(runs[i], 1) << i << " of " << count;
  }
}

TEST(ParallelTasks, NestedCallsRunEverything) {
  std::vector<std::vector<int>> runs(6, std::vector<int>(9, 0));
  std::atomic<int> total{0};
  ThreadBudget budget(3);
  ParallelTasks(
      runs.size(),
      [&](size_t i) {
        ParallelTasks(
            runs[i].size(),
            [&](size_t j) {
              ParallelTasks(
                  3, [&](size_t) { ++total; }, &budget);
              ++runs[i][j];
            },
            &budget);
      },
      &budget);
  for (const auto& row : runs) {
    for (int r : row) EXPECT_EQ(r, 1);
  }
  EXPECT_EQ(total.load(), 6 * 9 * 3);
  // The threads claimed are given back: a later call still runs everything.
  std::atomic<int> later{0};
  ParallelTasks(
      50, [&](size_t) { ++later; }, &budget);
  EXPECT_EQ(later.load(), 50);
  EXPECT_EQ(budget.Claim(100), 2);  // all three threads but the caller's are free again
}

TEST(ParallelTasks, WithoutABudgetEverythingRunsOnTheCallersThread) {
  const std::thread::id caller = std::this_thread::get_id();
  int elsewhere = 0;
  ParallelTasks(
      20, [&](size_t) { elsewhere += std::this_thread::get_id() != caller; }, nullptr);
  EXPECT_EQ(elsewhere, 0);
}

TEST(ParallelTasks, TheLowestIndexExceptionIsRethrownAfterAllRan) {
  for (int repeat = 0; repeat < 20; ++repeat) {
    std::atomic<int> ran{0};
    try {
      ThreadBudget budget(4);
      ParallelTasks(
          40,
          [&](size_t i) {
            ++ran;
            if (i == 31 || i == 7 || i == 22) throw std::runtime_error("task " + std::to_string(i));
          },
          &budget);
      FAIL() << "nothing was thrown";
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), "task 7");
    }
    EXPECT_EQ(ran.load(), 40);
  }
}

}  // namespace
}  // namespace alloycolor
