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

// Whose CPU time a stage counts: the whole process's (a stage that runs alone and may use
// helper threads), or the calling thread's (a stage that runs beside others, such as one
// position measured while another thread measures the next; helper threads it starts are not
// counted).
enum class CpuClock { kProcess, kThread };

// Adds the wall time and the CPU time of its scope to `stage` in the two maps (either may be
// null).
class StageTimer {
 public:
  StageTimer(std::map<std::string, double>* wall, std::map<std::string, double>* cpu,
             std::string stage, CpuClock clock = CpuClock::kProcess)
      : wall_(wall),
        cpu_(cpu),
        stage_(std::move(stage)),
        clock_(clock),
        start_(std::chrono::steady_clock::now()),
        cpu_start_(Now()) {}
  ~StageTimer() {
    if (wall_) {
      (*wall_)[stage_] +=
          std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    }
    if (cpu_) (*cpu_)[stage_] += Now() - cpu_start_;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double Now() const {
    return clock_ == CpuClock::kProcess ? ProcessCpuSeconds() : ThreadCpuSeconds();
  }
  std::map<std::string, double>* wall_;
  std::map<std::string, double>* cpu_;
  std::string stage_;
  CpuClock clock_;
  std::chrono::steady_clock::time_point start_;
  double cpu_start_;
};

}  // namespace brdfrig::reconstruct
