// The run engine: executes a plan on a rig into a session store.
//
// For each position: move the axes (at once when the plan allows), settle, take the bracket
// (metering first when auto-bracketing), hand every downloaded frame to the writer thread
// (check + durable write + record), which overlaps the move to the next position.
//
// States and their rules:
//   idle ──Run──► moving ──in position──► acquiring ──bracket taken──► moving (next) │ done
//   moving/acquiring ──Pause (at the next safe point: before a move or a shot)──► paused
//     (entered once the axes are stopped and every frame taken so far is recorded)
//   paused ──Resume──► the state it left;  any ──Abort──► done (aborted)
//   moving/acquiring ──recoverable fault──► fault ──recovered──► moving/acquiring
//   fault ──retries exhausted / fault not recoverable──► done (failed)
// On every stop (pause, abort, failure, done) the axes are stopped. Frames already downloaded
// are still recorded when the run stops. A position is the unit of redo: resuming a session
// redoes its incomplete positions only; a frame failing its check redoes its position.
//
// Fault policy (RetryPolicy): camera gone → Reopen, then retry the shot; camera busy,
// timeout or I/O error → back off and retry; axis alarm → ResetAlarm, retry the move; axis
// timeout or communication error → back off and retry; axis limits, bad settings, storage full
// and write errors → failed at once. Every operation gets at most max_attempts tries with
// exponential back-off between them.
#pragma once

#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "acquire/frame_writer.h"
#include "acquire/plan.h"
#include "acquire/session_store.h"
#include "rig/rig_file.h"

namespace brdfrig::acquire {

enum class RunState { kIdle, kMoving, kAcquiring, kPaused, kFault, kDone };
const char* RunStateName(RunState state);

struct RetryPolicy {
  int max_attempts = 5;            // tries per move or shot, the first included
  double initial_backoff_s = 0.5;  // wait before the second try; doubles each time
  double max_backoff_s = 10;
  int max_position_redos = 2;  // redos of one position whose frame failed its check
  void Validate() const;
};

struct RunOptions {
  // Record on a writer thread overlapping the next move (false: record before moving on, the
  // serial baseline of the benchmark).
  bool overlap = true;
  RetryPolicy retry;
  void Validate() const;
};

struct RunProgress {
  RunState state = RunState::kIdle;
  int position = 0;   // 0-based index of the position being worked on
  int positions = 0;  // planned positions
  int frame = 0;      // shot within the position's bracket
  int frames_per_position = 0;
  int frames_recorded = 0;  // in the session, all runs included
  int frames_total = 0;
  double eta_s = 0;            // model time left
  double last_saturation = 0;  // saturated fraction of the last recorded frame
  std::string message;         // the last event (fault, retry, ...)
};

// Times in the engine's model of the session: device durations as the devices report them
// (virtual for the simulator) plus host time measured where it is on the critical path.
struct RunTiming {
  double session_s = 0;      // from the first move to the last frame recorded
  double unavoidable_s = 0;  // longest move per position + settle + exposures + downloads
  double moves_s = 0, settle_s = 0, exposures_s = 0, downloads_s = 0;
  double host_s = 0;  // checking, writing, recording
  double wall_s = 0;  // real elapsed time of Run
  double Ratio() const { return unavoidable_s > 0 ? session_s / unavoidable_s : 0; }
};

struct RunSummary {
  ExitStatus status = ExitStatus::kFailed;
  std::string reason;
  int positions_done = 0;   // this run
  int frames_recorded = 0;  // this run
  int retries = 0;
  int redos = 0;
  RunTiming timing;
  std::string ToString() const;  // one line
};

class RunEngine {
 public:
  using ProgressCallback = std::function<void(const RunProgress&)>;
  // `rig` and `store` must outlive the engine; the plan must have passed CheckPlan.
  RunEngine(rig::Rig& rig, SessionStore& store, Plan plan, RunOptions options,
            ProgressCallback on_progress = {});

  // Blocks until done. `resumed`: the session has earlier runs to continue.
  RunSummary Run(bool resumed);

  // Thread-safe controls (from a signal thread, the daemon's API, ...).
  void Pause();
  void Resume();
  void Abort(const std::string& reason);
  RunProgress Progress() const;

 private:
  struct Stop {
    ExitStatus status;
    std::string reason;
  };

  void CapturePosition(int p);
  void MoveTo(int p);
  void MoveAxesOnce(const geometry::AxisPositions& axes);
  std::vector<rig::Frame> Shoot(int p, double exposure_s, double* actual_s);
  std::vector<double> Meter(int p);
  void CheckControls();
  void CheckWriter();
  void Fault(int p, const std::string& what, int attempt);
  void Backoff(int attempt);
  void StopAxes();
  void SetState(RunState state, const std::string& message = "");
  void Publish();

  rig::Rig& rig_;
  SessionStore& store_;
  Plan plan_;
  RunOptions options_;
  ProgressCallback on_progress_;
  std::optional<FrameWriter> writer_;

  mutable std::mutex mutex_;
  std::condition_variable control_changed_;
  bool pause_requested_ = false;
  std::optional<std::string> abort_reason_;
  RunProgress progress_;
  int recorded_this_run_ = 0;
  std::mutex publish_mutex_;

  // Model clock (engine side) and what it is made of.
  double clock_s_ = 0;
  RunTiming timing_;
  RunSummary summary_;
  geometry::AxisPositions readings_;      // last read-back of every axis
  std::vector<double> position_model_s_;  // model time per completed position (for the ETA)
  double estimated_position_s_ = 0;       // the plan check's estimate, before any is done
  double remaining_ = 0;                  // positions left, the current one included
};

}  // namespace brdfrig::acquire
