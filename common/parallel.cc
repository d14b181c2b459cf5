#include "common/parallel.h"

#include <sched.h>

#include <algorithm>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace brdfrig {

int DefaultThreadCount() {
  // The CPUs this process may run on: a Slurm task bound to its --cpus-per-task (or a
  // `taskset`) gets that many threads, not one per core of the node.
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  const int hardware = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  if (::sched_getaffinity(0, sizeof allowed, &allowed) != 0) return hardware;
  return std::clamp(CPU_COUNT(&allowed), 1, hardware);
}

void ParallelFor(std::size_t count, const std::function<void(std::size_t, std::size_t)>& body,
                 int threads) {
  if (count == 0) return;
  const std::size_t workers =
      std::min<std::size_t>(count, threads > 0 ? threads : DefaultThreadCount());
  if (workers == 1) {
    body(0, count);
    return;
  }
  std::exception_ptr first_error;
  std::mutex error_mutex;
  std::vector<std::thread> pool;
  pool.reserve(workers);
  for (std::size_t w = 0; w < workers; ++w) {
    const std::size_t begin = count * w / workers;
    const std::size_t end = count * (w + 1) / workers;
    pool.emplace_back([&, begin, end] {
      try {
        body(begin, end);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
      }
    });
  }
  for (std::thread& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace brdfrig
