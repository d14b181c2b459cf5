#include "batch/slurm.h"

#include <signal.h>

#include <array>
#include <sstream>

#include "batch/array_spec.h"
#include "common/error.h"
#include "common/subprocess.h"

namespace brdfrig::batch {

namespace {

std::string Trimmed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

std::string JobIdList(const std::vector<Submission>& submissions) {
  std::string ids;
  for (const Submission& s : submissions) ids += (ids.empty() ? "" : ",") + s.job_id;
  return ids;
}

volatile sig_atomic_t deferred_signal = 0;

void RememberSignal(int sig) { deferred_signal = sig; }

// From the moment sbatch starts until its job id is in submissions.txt, SIGINT, SIGTERM and
// SIGHUP are held back and acted on afterwards: a job the scheduler accepted but nobody
// recorded would be submitted a second time by the next `collect --resubmit`. sbatch itself
// starts with the default actions (exec resets handled signals). Signals the caller ignores
// stay ignored.
class DeferTerminationSignals {
 public:
  DeferTerminationSignals() {
    deferred_signal = 0;
    struct sigaction remember {};
    remember.sa_handler = RememberSignal;
    sigemptyset(&remember.sa_mask);
    for (std::size_t i = 0; i < kSignals.size(); ++i) {
      ::sigaction(kSignals[i], nullptr, &old_[i]);
      if (old_[i].sa_handler != SIG_IGN) ::sigaction(kSignals[i], &remember, nullptr);
    }
  }
  ~DeferTerminationSignals() {
    for (std::size_t i = 0; i < kSignals.size(); ++i) ::sigaction(kSignals[i], &old_[i], nullptr);
    if (deferred_signal != 0) ::raise(deferred_signal);
  }
  DeferTerminationSignals(const DeferTerminationSignals&) = delete;
  DeferTerminationSignals& operator=(const DeferTerminationSignals&) = delete;

 private:
  static constexpr std::array<int, 3> kSignals = {SIGINT, SIGTERM, SIGHUP};
  std::array<struct sigaction, 3> old_{};
};

}  // namespace

Submission SubmitArray(const JobDir& dir, const std::vector<int>& indices, int throttle) {
  const std::string spec = ArraySpec(indices, throttle);
  const std::vector<std::string> argv = {"sbatch", "--parsable", "--array=" + spec,
                                         dir.script().string()};
  const DeferTerminationSignals defer;
  const ProcessResult run = RunProcess(argv);
  if (!run.ok()) {
    throw Error(ShellQuoted(argv) + " failed (exit status " + std::to_string(run.exit_status) +
                "): " + Trimmed(run.err + run.out));
  }
  // --parsable prints "<job id>" or "<job id>;<cluster>".
  std::string id = Trimmed(run.out);
  id = id.substr(0, id.find(';'));
  if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos) {
    throw Error(ShellQuoted(argv) + " printed \"" + Trimmed(run.out) + "\", not a job id");
  }
  const Submission submission{id, spec};
  RecordSubmission(dir, submission);
  return submission;
}

void ParseSchedulerLines(const std::string& text, const std::vector<std::string>& job_ids,
                         std::map<int, TaskState>& tasks) {
  // Lines in the order of job_ids, so a resubmission's state replaces the first attempt's.
  std::map<std::string, std::vector<std::pair<std::vector<int>, TaskState>>> by_job;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string id, state, reason;
    if (!std::getline(fields, id, '|') || !std::getline(fields, state, '|')) continue;
    std::getline(fields, reason, '|');
    const std::size_t underscore = id.find('_');
    if (underscore == std::string::npos) continue;  // not an array task (or a job step)
    const std::string job = id.substr(0, underscore);
    std::vector<int> indices;
    try {
      indices = ExpandArraySpec(id.substr(underscore + 1));
    } catch (const Error&) {
      continue;  // "123_4.batch" step lines and the like
    }
    // sacct says "CANCELLED by 0": the first word is the state.
    state = state.substr(0, state.find(' '));
    by_job[job].push_back({indices, TaskState{job, state, Trimmed(reason)}});
  }
  for (const std::string& job : job_ids) {
    for (const auto& [indices, state] : by_job[job]) {
      for (int i : indices) tasks[i] = state;
    }
  }
}

int SchedulerView::Active() const {
  int active = 0;
  for (const auto& [index, state] : tasks) active += state.Active();
  return active;
}

SchedulerView QueryScheduler(const std::vector<Submission>& submissions) {
  SchedulerView view;
  if (submissions.empty()) {
    view.source = "nothing submitted yet";
    return view;
  }
  std::vector<std::string> ids;
  for (const Submission& s : submissions) ids.push_back(s.job_id);
  const ProcessResult sacct = RunProcess(
      {"sacct", "-n", "-P", "-X", "-j", JobIdList(submissions), "-o", "JobID,State,ExitCode"});
  if (sacct.ok()) {
    ParseSchedulerLines(sacct.out, ids, view.tasks);
    view.source = "sacct";
    return view;
  }
  const ProcessResult squeue =
      RunProcess({"squeue", "-h", "-t", "all", "-j", JobIdList(submissions), "-o", "%i|%T|%r"});
  if (squeue.ok()) {
    ParseSchedulerLines(squeue.out, ids, view.tasks);
    view.source = "squeue";
    return view;
  }
  view.source = "neither sacct (" + Trimmed(sacct.err) + ") nor squeue (" + Trimmed(squeue.err) +
                ") answered";
  return view;
}

}  // namespace brdfrig::batch
