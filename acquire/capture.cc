#include "acquire/capture.h"

#include "acquire/plan_check.h"
#include "acquire/session_store.h"
#include "common/atomic_file.h"
#include "session/rig_snapshot.h"

namespace brdfrig::acquire {

using session::RigChangesSince;

namespace fs = std::filesystem;

namespace {

// "sessions/s1/" names the session s1 too.
fs::path SessionDir(const fs::path& output) {
  fs::path dir = output.lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  return dir;
}

}  // namespace

void CaptureOptions::Validate() const {
  if (rig_file.empty()) throw OptionsError("capture: no rig file given (--rig)");
  if (output_dir.empty()) throw OptionsError("capture: no session directory given (-o)");
  if (plan_file.empty() && !resume) throw OptionsError("capture: no plan given (--plan)");
  ValidateSessionName(SessionDir(output_dir).filename().string());
  run.Validate();
}

std::string CaptureSummary::ToString() const {
  return session_dir.string() + (resumed ? " (resumed): " : ": ") + run.ToString();
}

CaptureSummary RunCapture(const CaptureOptions& options) {
  options.Validate();
  CaptureSummary summary;
  const fs::path dir = SessionDir(options.output_dir);
  summary.session_dir = dir;
  const geometry::RigDescription description = rig::ReadRigDescription(options.rig_file);
  // One owner of the rig: a daemon or another capture using it makes this fail here, before
  // a session is touched or a device opened.
  rig::RigLock owner = rig::RigLock::Acquire(options.rig_file);
  std::unique_ptr<SessionStore> store;
  Plan plan;
  if (options.resume && !fs::exists(dir) && options.plan_file.empty()) {
    throw Error("cannot resume: there is no session at '" + dir.string() +
                "' (check the path, or give --plan to start it)");
  }
  // Leftovers of a capture killed while creating a session beside this one.
  for (const std::string& line : CleanStaleSessionTemporaries(
           dir.parent_path().empty() ? fs::path(".") : dir.parent_path())) {
    summary.warnings.push_back(line);
  }
  if (options.resume && fs::exists(dir)) {
    store = SessionStore::Open(dir);
    // The session's own plan is the one to finish; a different plan file is a mistake.
    plan = LoadPlanString(store->PlanText(), store->PlanSource());
    if (!options.plan_file.empty() && ReadFileToString(options.plan_file) != plan.text) {
      throw Error(options.plan_file.string() + " differs from the plan of session " + dir.string() +
                  "; resume without --plan or with the same plan");
    }
    summary.resumed = true;
  } else {
    plan = LoadPlanFile(options.plan_file);
  }
  // A designed plan gets its positions from the rig (deterministic, so a resume continues it).
  ResolvePlan(&plan, description.geometry);
  const PlanCheckReport check = CheckPlan(plan, description);
  if (!check.ok()) {
    std::string message = "the plan cannot run on this rig:";
    for (const std::string& e : check.errors) message += "\n  " + e;
    throw Error(message);
  }
  summary.warnings.insert(summary.warnings.end(), check.warnings.begin(), check.warnings.end());
  rig::Rig rig = rig::OpenRig(options.rig_file, std::move(owner));
  if (!store) store = SessionStore::Create(dir, plan, description);
  if (!summary.resumed) {
    for (const std::string& w : check.warnings) store->LogEvent("warning", -1, "plan check: " + w);
  } else {
    // Resuming with another rig configuration is allowed (a drive replaced, a fixed typo) but
    // recorded: the frames after this point were taken with it.
    for (const std::string& change : RigChangesSince(dir, description)) {
      store->LogEvent("warning", -1, "resume: " + change);
      summary.warnings.push_back(change);
    }
  }
  RunEngine engine(rig, *store, plan, options.run, options.on_progress);
  if (!options.on_engine) {
    summary.run = engine.Run(summary.resumed);
    return summary;
  }
  options.on_engine(&engine);
  try {
    summary.run = engine.Run(summary.resumed);
  } catch (...) {
    options.on_engine(nullptr);
    throw;
  }
  options.on_engine(nullptr);
  return summary;
}

}  // namespace brdfrig::acquire
