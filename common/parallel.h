// A minimal parallel loop over an index range on std::threads: the work is split into
// contiguous chunks so results are deterministic whatever the thread count.
#pragma once

#include <cstddef>
#include <functional>

namespace brdfrig {

// Number of worker threads used by ParallelFor: the CPUs this process is allowed to run on
// (its affinity mask, which Slurm and taskset set), at most the hardware's, at least 1.
int DefaultThreadCount();

// Calls body(begin, end) on disjoint chunks covering [0, count). Blocks until all are done.
// Exceptions thrown by body are rethrown (the first one) after every chunk finished.
void ParallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads = 0);

}  // namespace brdfrig
