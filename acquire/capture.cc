#include "acquire/capture.h"

#include "acquire/plan_check.h"
#include "acquire/session_store.h"
#include "common/atomic_file.h"

namespace brdfrig::acquire {

namespace fs = std::filesystem;

void CaptureOptions::Validate() const {
  if (rig_file.empty()) throw OptionsError("capture: no rig file given (--rig)");
  if (output_dir.empty()) throw OptionsError("capture: no session directory given (-o)");
  if (plan_file.empty() && !resume) throw OptionsError("capture: no plan given (--plan)");
  ValidateSessionName(output_dir.filename().string());
  run.Validate();
}

std::string CaptureSummary::ToString() const {
  return session_dir.string() + (resumed ? " (resumed): " : ": ") + run.ToString();
}

CaptureSummary RunCapture(const CaptureOptions& options) {
  options.Validate();
  CaptureSummary summary;
  summary.session_dir = options.output_dir;
  const rig::RigDescription description = rig::ReadRigDescription(options.rig_file);
  std::unique_ptr<SessionStore> store;
  Plan plan;
  if (options.resume && fs::exists(options.output_dir)) {
    store = SessionStore::Open(options.output_dir);
    // The session's own plan is the one to finish; a different plan file is a mistake.
    plan = LoadPlanString(store->PlanText(), store->PlanSource());
    if (!options.plan_file.empty() && ReadFileToString(options.plan_file) != plan.text) {
      throw Error(options.plan_file.string() + " differs from the plan of session " +
                  options.output_dir.string() + "; resume without --plan or with the same plan");
    }
    summary.resumed = true;
  } else {
    plan = LoadPlanFile(options.plan_file);
  }
  const PlanCheckReport check = CheckPlan(plan, description);
  if (!check.ok()) {
    std::string message = "the plan cannot run on this rig:";
    for (const std::string& e : check.errors) message += "\n  " + e;
    throw Error(message);
  }
  rig::Rig rig = rig::OpenRig(options.rig_file);
  if (!store) store = SessionStore::Create(options.output_dir, plan, description);
  RunEngine engine(rig, *store, plan, options.run, options.on_progress);
  if (options.on_engine) options.on_engine(engine);
  summary.run = engine.Run(summary.resumed);
  return summary;
}

}  // namespace brdfrig::acquire
