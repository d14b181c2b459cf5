// The thread count follows the CPUs a process may use (what Slurm's CPU binding or taskset
// gives it), and a parallel loop's chunks cover the range exactly once whatever that count.
#include "common/parallel.h"

#include <sched.h>

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

namespace brdfrig {
namespace {

TEST(ParallelTest, DefaultThreadCountIsTheAffinityMaskNotTheWholeMachine) {
  cpu_set_t original;
  CPU_ZERO(&original);
  ASSERT_EQ(::sched_getaffinity(0, sizeof original, &original), 0);
  EXPECT_EQ(DefaultThreadCount(),
            std::min<int>(CPU_COUNT(&original), std::thread::hardware_concurrency()));
  // Bound to one CPU, as a Slurm task with --cpus-per-task=1 under task/affinity is.
  int first = 0;
  while (!CPU_ISSET(first, &original)) ++first;
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(first, &one);
  ASSERT_EQ(::sched_setaffinity(0, sizeof one, &one), 0);
  EXPECT_EQ(DefaultThreadCount(), 1);
  ASSERT_EQ(::sched_setaffinity(0, sizeof original, &original), 0);
}

TEST(ParallelTest, ChunksCoverTheRangeOnceForAnyThreadCount) {
  for (int threads : {1, 2, 3, 8}) {
    std::vector<std::atomic<int>> seen(100);
    ParallelFor(
        seen.size(),
        [&](std::size_t begin, std::size_t end) {
          for (std::size_t i = begin; i < end; ++i) ++seen[i];
        },
        threads);
    for (const std::atomic<int>& s : seen) EXPECT_EQ(s.load(), 1) << threads << " threads";
  }
}

}  // namespace
}  // namespace brdfrig
