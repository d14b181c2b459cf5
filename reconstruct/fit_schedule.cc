#include "reconstruct/fit_schedule.h"

#include <algorithm>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

#include "common/check.h"
#include "common/parallel.h"

namespace brdfrig::reconstruct {

void RunFitTasks(const std::vector<FitTask>& tasks, int threads) {
  const int n = static_cast<int>(tasks.size());
  if (n == 0) return;
  std::vector<std::vector<int>> waiting_on(n);  // task → the tasks that wait for it
  std::vector<int> missing(n, 0);               // unfinished dependencies
  for (int t = 0; t < n; ++t) {
    for (int d : tasks[t].after) {
      BRDFRIG_CHECK(d >= 0 && d < n && d != t, "fit task dependency out of range");
      waiting_on[d].push_back(t);
      ++missing[t];
    }
  }
  // Priority: the task's cost plus the costliest chain that waits on it. Tasks are visited in
  // reverse topological order (Kahn's order, reversed), so every dependent is done first.
  std::vector<int> order;
  {
    std::vector<int> left = missing, ready;
    for (int t = 0; t < n; ++t) {
      if (left[t] == 0) ready.push_back(t);
    }
    while (!ready.empty()) {
      const int t = ready.back();
      ready.pop_back();
      order.push_back(t);
      for (int w : waiting_on[t]) {
        if (--left[w] == 0) ready.push_back(w);
      }
    }
    BRDFRIG_CHECK(static_cast<int>(order.size()) == n, "fit task dependencies form a cycle");
  }
  std::vector<double> priority(n, 0);
  for (auto it = order.rbegin(); it != order.rend(); ++it) {
    double chain = 0;
    for (int w : waiting_on[*it]) chain = std::max(chain, priority[w]);
    priority[*it] = tasks[*it].expected_cost + chain;
  }

  std::mutex mutex;
  std::condition_variable changed;
  std::vector<int> ready;
  for (int t = 0; t < n; ++t) {
    if (missing[t] == 0) ready.push_back(t);
  }
  int finished = 0;
  std::exception_ptr first_error;
  const auto worker = [&] {
    std::unique_lock lock(mutex);
    while (true) {
      changed.wait(lock, [&] { return !ready.empty() || finished == n; });
      if (ready.empty()) return;  // finished == n
      // The ready task with the highest priority; ties by index, so the order is reproducible.
      const auto best = std::max_element(ready.begin(), ready.end(), [&](int a, int b) {
        return priority[a] < priority[b] || (priority[a] == priority[b] && a > b);
      });
      const int t = *best;
      ready.erase(best);
      lock.unlock();
      try {
        tasks[t].run();
      } catch (...) {
        std::lock_guard error_lock(mutex);
        if (!first_error) first_error = std::current_exception();
      }
      lock.lock();
      ++finished;
      for (int w : waiting_on[t]) {
        if (--missing[w] == 0) ready.push_back(w);
      }
      changed.notify_all();
    }
  };
  const int workers = std::clamp(threads > 0 ? threads : DefaultThreadCount(), 1, n);
  std::vector<std::thread> pool;
  for (int w = 1; w < workers; ++w) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace brdfrig::reconstruct
