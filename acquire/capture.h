// `brdfrig capture`: one session in the foreground, the same engine the daemon runs. The rig's
// backends must be registered before (the application registers the simulator and the
// hardware backends; acquire/ does not know which exist).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "acquire/run_engine.h"

namespace brdfrig::acquire {

struct CaptureOptions {
  std::filesystem::path rig_file;
  std::filesystem::path plan_file;   // may be empty when resuming (the session keeps its plan)
  std::filesystem::path output_dir;  // the session directory; its name must be a valid name
  // Continue the session in output_dir (start it when it does not exist yet).
  bool resume = false;
  RunOptions run;
  RunEngine::ProgressCallback on_progress;
  // Called with the engine once it exists (e.g. to wire SIGINT to Abort), and with nullptr
  // before it is destroyed, whatever the run's end; may be empty.
  std::function<void(RunEngine*)> on_engine;
  void Validate() const;
};

struct CaptureSummary {
  std::filesystem::path session_dir;
  bool resumed = false;
  std::vector<std::string> warnings;  // the plan check's (e.g. highlight not on the cut-out)
  RunSummary run;
  std::string ToString() const;
};

// Throws brdfrig::Error for anything that prevents the run from starting (bad plan, rig that
// cannot be opened, existing session without --resume); the run's own end is in the summary.
CaptureSummary RunCapture(const CaptureOptions& options);

}  // namespace brdfrig::acquire
