#include "batch/follow.h"

#include <chrono>
#include <sstream>
#include <thread>

namespace brdfrig::batch {

using Outcome = CollectedItem::Outcome;

std::string ProgressLine(const CollectReport& report, const SchedulerView& scheduler) {
  int running = 0, pending = 0;
  for (const auto& [index, state] : scheduler.tasks) {
    running += state.state == "RUNNING" || state.state == "COMPLETING";
    pending += state.Active() && state.state != "RUNNING" && state.state != "COMPLETING";
  }
  const int with_result = report.Count(Outcome::kSucceeded) + report.Count(Outcome::kPartial) +
                          report.Count(Outcome::kFailed);
  std::ostringstream s;
  s << report.items.size() << " item(s): " << with_result << " with a result ("
    << report.Count(Outcome::kSucceeded) << " succeeded, " << report.Count(Outcome::kPartial)
    << " partial, " << report.Count(Outcome::kFailed) << " failed), " << running << " running, "
    << pending << " pending (scheduler: " << scheduler.source << ")";
  return s.str();
}

CollectReport FollowJob(const JobDir& dir, bool wait, double interval_s,
                        const std::function<void(const std::string&)>& on_progress) {
  std::string last;
  for (;;) {
    const SchedulerView scheduler = QueryScheduler(ReadSubmissions(dir));
    CollectReport report = Collect(dir, scheduler);
    const std::string line = ProgressLine(report, scheduler);
    if (line != last && on_progress) on_progress(line);
    last = line;
    if (!wait || scheduler.Active() == 0) return report;
    std::this_thread::sleep_for(std::chrono::duration<double>(interval_s));
  }
}

}  // namespace brdfrig::batch
