// Wall and CPU time of the reconstruction's stages. CPU time is the whole process's (every
// thread's) so that a stage that runs in parallel shows what it costs the machine, and so that
// a benchmark on a shared machine can be read by CPU seconds, which other users' load barely
// moves, rather than by wall time alone.
#pragma once

#include <time.h>

#include <chrono>
#include <map>
#include <string>

namespace brdfrig::reconstruct {

// CPU seconds used so far by this process (all threads) or by the calling thread.
inline double ProcessCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}
inline double ThreadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

// Adds the wall time and the process CPU time of its scope to `stage` in the two maps (either
// may be null).
class StageTimer {
 public:
  StageTimer(std::map<std::string, double>* wall, std::map<std::string, double>* cpu,
             std::string stage)
      : wall_(wall),
        cpu_(cpu),
        stage_(std::move(stage)),
        start_(std::chrono::steady_clock::now()),
        cpu_start_(ProcessCpuSeconds()) {}
  ~StageTimer() {
    if (wall_) {
      (*wall_)[stage_] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    if (cpu_) (*cpu_)[stage_] += ProcessCpuSeconds() - cpu_start_;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  std::map<std::string, double>* wall_;
  std::map<std::string, double>* cpu_;
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
  double cpu_start_;
};

}  // namespace brdfrig::reconstruct
