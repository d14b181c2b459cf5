// Runs the ladder's fits (every rung on every position, and on each leave-one-position-out
// fold) as tasks on a few threads, in an order that respects which fit starts which (a fold's
// GGX fit starts from the full GGX fit; the table rung starts from a GGX fit of the same
// positions). Each task is single-threaded and writes only its own result, so the results are
// the same, bit for bit, whatever the thread count and the order: only the wall time changes.
//
// Why not one ParallelFor over the folds: the full fits ran one after another before the folds,
// and the folds were cut in contiguous chunks whose costs differ severalfold (a table fit costs
// ten prior fits), so one thread idled while the other finished. Here a free thread takes the
// ready task that heads the longest chain of remaining work (its expected cost plus that of
// the tasks waiting on it), which keeps both cores busy until the end.
#pragma once

#include <functional>
#include <vector>

namespace brdfrig::reconstruct {

struct FitTask {
  std::function<void()> run;  // must not throw (a task records its own failure)
  std::vector<int> after;     // indices of the tasks that must finish first
  double expected_cost = 1;   // relative, for the order only (results never depend on it)
};

// Runs every task once on `threads` threads (0: DefaultThreadCount()) and returns when all have
// finished. Dependencies must point to other tasks of the list and form no cycle. If a task
// throws anyway, the first exception is rethrown after every started task has finished.
void RunFitTasks(const std::vector<FitTask>& tasks, int threads = 0);

}  // namespace brdfrig::reconstruct
