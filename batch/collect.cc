#include "batch/collect.h"

#include <cstdio>
#include <sstream>

#include "batch/manifest.h"
#include "batch/task.h"
#include "common/display_text.h"
#include "common/error.h"

namespace brdfrig::batch {

namespace fs = std::filesystem;
using Outcome = CollectedItem::Outcome;

std::string OutcomeName(Outcome outcome) {
  switch (outcome) {
    case Outcome::kSucceeded:
      return "succeeded";
    case Outcome::kPartial:
      return "partial";
    case Outcome::kFailed:
      return "FAILED";
    case Outcome::kNoResult:
      return "NO RESULT";
    case Outcome::kActive:
      return "active";
  }
  return "?";
}

int CollectReport::Count(Outcome outcome) const {
  int n = 0;
  for (const CollectedItem& item : items) n += item.outcome == outcome;
  return n;
}

int CollectReport::NotDone() const {
  return Count(Outcome::kFailed) + Count(Outcome::kNoResult) + Count(Outcome::kActive);
}

std::vector<int> CollectReport::ToResubmit() const {
  std::vector<int> indices;
  for (const CollectedItem& item : items) {
    if (item.outcome == Outcome::kFailed || item.outcome == Outcome::kNoResult) {
      indices.push_back(item.index);
    }
  }
  return indices;
}

int CollectReport::ExitStatus() const {
  if (NotDone() > 0) return 1;
  return Count(Outcome::kPartial) > 0 ? 3 : 0;
}

std::string CollectReport::Summary() const {
  std::ostringstream s;
  for (const CollectedItem& item : items) {
    if (item.outcome == Outcome::kSucceeded) continue;
    s << OutcomeName(item.outcome) << "  " << item.index << " "
      << DisplayPath(item.capture.string()) << ": " << OneLine(item.why) << "\n";
  }
  s << items.size() << " item(s): " << Count(Outcome::kSucceeded) << " succeeded, "
    << Count(Outcome::kPartial) << " partial, " << Count(Outcome::kFailed) << " failed, "
    << Count(Outcome::kNoResult) << " without a result, " << Count(Outcome::kActive)
    << " pending or running";
  if (!up_to_date.empty()) s << "; " << up_to_date.size() << " up to date when prepared";
  s << " (scheduler: " << scheduler << ")\n";
  return s.str();
}

CollectReport Collect(const JobDir& dir, const SchedulerView& scheduler) {
  const Manifest manifest = ReadManifest(dir.manifest());
  CollectReport report;
  report.scheduler = scheduler.source;
  for (const fs::path& p : manifest.up_to_date) report.up_to_date.push_back(p.string());
  for (const ManifestItem& m : manifest.items) {
    CollectedItem item;
    item.index = m.index;
    item.capture = m.capture;
    item.material = m.material;
    const auto state = scheduler.tasks.find(m.index);
    const bool active = state != scheduler.tasks.end() && state->second.Active();
    if (active) {
      // A task running again (resubmitted) makes an earlier result stale.
      item.outcome = Outcome::kActive;
      item.why =
          state->second.state + " in job " + state->second.job_id + "_" + std::to_string(m.index);
    } else if (std::error_code error; fs::exists(fs::symlink_status(dir.result(m.index), error))) {
      // A result that cannot be read (torn by hand, a FIFO, another item's) is this item's
      // failure, to be run again; the other items are still reported.
      try {
        const TaskResult result = ReadTaskResult(dir.result(m.index));
        item.seconds = result.item.seconds;
        item.outcome = result.exit_status == 0   ? Outcome::kSucceeded
                       : result.exit_status == 3 ? Outcome::kPartial
                                                 : Outcome::kFailed;
        item.why = result.item.message;
        for (const std::string& d : result.item.dropped) item.why += "; dropped " + d;
        for (const std::string& d : result.item.degraded) item.why += "; degraded " + d;
        if (!result.job.empty()) item.why += " (" + result.job + " on " + result.host + ")";
      } catch (const Error& e) {
        item.outcome = Outcome::kFailed;
        item.why = std::string("its result cannot be read: ") + e.what();
      }
    } else if (state != scheduler.tasks.end()) {
      item.outcome = Outcome::kNoResult;
      item.why = "job " + state->second.job_id + "_" + std::to_string(m.index) + " ended " +
                 state->second.state +
                 (state->second.reason.empty() || state->second.reason == "None"
                      ? ""
                      : " (" + state->second.reason + ")") +
                 " without writing a result";
    } else {
      item.outcome = Outcome::kNoResult;
      item.why =
          "no result, and the scheduler does not know the task (never submitted, or "
          "ended long ago: see " +
          dir.logs().string() + ")";
    }
    report.items.push_back(item);
  }
  return report;
}

}  // namespace brdfrig::batch
