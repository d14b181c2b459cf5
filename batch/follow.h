// `brdfrig batch status`: the progress of a job directory's arrays, once or until no task is
// pending or running any more.
#pragma once

#include <functional>
#include <string>

#include "batch/collect.h"

namespace brdfrig::batch {

// "12 item(s): 7 with a result (6 succeeded, 1 failed), 2 running, 3 pending (scheduler: ...)"
std::string ProgressLine(const CollectReport& report, const SchedulerView& scheduler);

// Queries the scheduler and collects; with `wait`, repeats every `interval_s` seconds while a
// task is pending or running, calling `on_progress` with each new progress line. Returns the
// last report.
CollectReport FollowJob(const JobDir& dir, bool wait, double interval_s,
                        const std::function<void(const std::string&)>& on_progress);

}  // namespace brdfrig::batch
