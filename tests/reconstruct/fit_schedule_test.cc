#include "reconstruct/fit_schedule.h"

#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

namespace brdfrig::reconstruct {
namespace {

// A diamond and a chain, on several thread counts: every task runs once, and only after the
// tasks it waits for have finished.
TEST(FitScheduleTest, EveryTaskRunsOnceAfterItsDependencies) {
  for (int threads : {1, 2, 4}) {
    std::mutex mutex;
    std::vector<int> finished_order;
    std::vector<FitTask> tasks(7);
    const std::vector<std::vector<int>> after = {{}, {0}, {0}, {1, 2}, {}, {4}, {5}};
    for (int t = 0; t < 7; ++t) {
      tasks[t].after = after[t];
      tasks[t].expected_cost = 1 + t % 3;
      tasks[t].run = [&, t] {
        std::lock_guard lock(mutex);
        finished_order.push_back(t);
      };
    }
    RunFitTasks(tasks, threads);
    ASSERT_EQ(finished_order.size(), 7u) << threads << " threads";
    std::vector<int> position(7, -1);
    for (int i = 0; i < 7; ++i) {
      EXPECT_EQ(position[finished_order[i]], -1) << "task ran twice";
      position[finished_order[i]] = i;
    }
    for (int t = 0; t < 7; ++t) {
      for (int d : after[t]) EXPECT_LT(position[d], position[t]) << t << " before " << d;
    }
  }
}

// Independent tasks really run at the same time on two threads: each waits (bounded) until
// the other has started.
TEST(FitScheduleTest, IndependentTasksRunConcurrently) {
  std::atomic<int> started = 0;
  std::atomic<bool> saw_both = true;
  std::vector<FitTask> tasks(2);
  for (FitTask& task : tasks) {
    task.run = [&] {
      ++started;
      for (int i = 0; i < 2000000 && started.load() < 2; ++i) std::this_thread::yield();
      if (started.load() < 2) saw_both = false;
    };
  }
  RunFitTasks(tasks, 2);
  EXPECT_TRUE(saw_both.load());
}

TEST(FitScheduleTest, RethrowsATaskExceptionAfterTheOthersFinish) {
  std::atomic<int> ran = 0;
  std::vector<FitTask> tasks(4);
  for (int t = 0; t < 4; ++t) {
    tasks[t].run = [&, t] {
      ++ran;
      if (t == 1) throw std::runtime_error("task 1 failed");
    };
  }
  EXPECT_THROW(RunFitTasks(tasks, 2), std::runtime_error);
  EXPECT_EQ(ran.load(), 4);
}

}  // namespace
}  // namespace brdfrig::reconstruct
