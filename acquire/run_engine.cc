#include "acquire/run_engine.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <exception>
#include <set>
#include <sstream>
#include <thread>

#include "acquire/auto_bracket.h"
#include "acquire/plan_check.h"
#include "acquire/test_hooks.h"

namespace brdfrig::acquire {
namespace {

using Clock = std::chrono::steady_clock;

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

std::string Seconds(double s) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g s", s);
  return text;
}

}  // namespace

const char* RunStateName(RunState state) {
  switch (state) {
    case RunState::kIdle:
      return "idle";
    case RunState::kMoving:
      return "moving";
    case RunState::kAcquiring:
      return "acquiring";
    case RunState::kPaused:
      return "paused";
    case RunState::kFault:
      return "fault";
    case RunState::kDone:
      return "done";
  }
  return "?";
}

void RetryPolicy::Validate() const {
  if (max_attempts < 1) throw OptionsError("retry.max_attempts must be >= 1");
  if (!(initial_backoff_s >= 0) || !(max_backoff_s >= initial_backoff_s)) {
    throw OptionsError("retry: need 0 <= initial_backoff_s <= max_backoff_s");
  }
  if (max_position_redos < 0) throw OptionsError("retry.max_position_redos must be >= 0");
}

void RunOptions::Validate() const { retry.Validate(); }

std::string RunSummary::ToString() const {
  char text[320];
  std::snprintf(text, sizeof text,
                ": %d positions, %d frames recorded in this run, %d retries, %d redos; session "
                "%.1f s vs unavoidable %.1f s (ratio %.3f), wall %.1f s",
                positions_done, frames_recorded, retries, redos, timing.session_s,
                timing.unavoidable_s, timing.Ratio(), timing.wall_s);
  return ExitStatusName(status) + (reason.empty() ? "" : " (" + reason + ")") + text;
}

RunEngine::RunEngine(rig::Rig& rig, SessionStore& store, Plan plan, RunOptions options,
                     ProgressCallback on_progress)
    : rig_(rig),
      store_(store),
      plan_(std::move(plan)),
      options_(options),
      on_progress_(std::move(on_progress)) {
  options_.Validate();
  if (!rig_.camera) throw Error("the rig has no camera");
  for (const PlannedPosition& p : plan_.positions) {
    for (const auto& [axis, angle] : p.axes) {
      if (!rig_.axes.count(axis)) {
        throw FileError(plan_.file, p.line, 0,
                        "the plan moves axis '" + axis + "' but " + rig_.description.file.string() +
                            " has no device for it");
      }
    }
  }
  // Until a position is done, the ETA comes from the plan check's estimate.
  const PlanCheckReport estimate = CheckPlan(plan_, rig_.description);
  estimated_position_s_ =
      estimate.EstimatedDurationS() / std::max<std::size_t>(1, plan_.positions.size());
  progress_.positions = static_cast<int>(plan_.positions.size());
  progress_.frames_per_position = plan_.BracketSize();
  progress_.frames_total = progress_.positions * progress_.frames_per_position;
}

void RunEngine::Pause() {
  std::lock_guard lock(mutex_);
  pause_requested_ = true;
  control_changed_.notify_all();
}

void RunEngine::Resume() {
  std::lock_guard lock(mutex_);
  pause_requested_ = false;
  control_changed_.notify_all();
}

void RunEngine::Abort(const std::string& reason) {
  std::lock_guard lock(mutex_);
  if (!abort_reason_) abort_reason_ = reason.empty() ? "aborted by the operator" : reason;
  control_changed_.notify_all();
}

RunProgress RunEngine::Progress() const {
  std::lock_guard lock(mutex_);
  return progress_;
}

void RunEngine::Publish() {
  if (!on_progress_) return;
  std::lock_guard publish(publish_mutex_);
  on_progress_(Progress());
}

void RunEngine::SetState(RunState state, const std::string& message) {
  {
    std::lock_guard lock(mutex_);
    progress_.state = state;
    if (!message.empty()) progress_.message = message;
  }
  Publish();
}

void RunEngine::StopAxes() {
  for (auto& [name, axis] : rig_.axes) {
    try {
      axis->Stop();
    } catch (const std::exception& e) {
      // Stopping is best effort: the drive's own fault handling takes over when it fails.
      store_.LogEvent("error", -1, "could not stop axis '" + name + "': " + e.what());
    }
  }
}

// Safe point: honours pause and abort requests.
void RunEngine::CheckControls() {
  CheckWriter();
  std::unique_lock lock(mutex_);
  if (abort_reason_) throw Stop{ExitStatus::kAborted, *abort_reason_};
  if (!pause_requested_) return;
  const RunState before = progress_.state;
  lock.unlock();
  StopAxes();
  // Paused means settled: every frame taken so far is recorded before the state says so.
  writer_->Drain();
  lock.lock();
  progress_.state = RunState::kPaused;
  progress_.message = "paused by the operator";
  lock.unlock();
  store_.LogEvent("info", progress_.position, "paused");
  Publish();
  const auto paused_at = Clock::now();
  lock.lock();
  control_changed_.wait(lock, [&] { return !pause_requested_ || abort_reason_; });
  if (abort_reason_) throw Stop{ExitStatus::kAborted, *abort_reason_};
  progress_.state = before;
  progress_.message = "resumed";
  lock.unlock();
  // Time spent paused is the operator's, not the rig's: it is kept out of the session model.
  store_.LogEvent("info", progress_.position,
                  "resumed after " + Seconds(Since(paused_at)) + " paused");
  Publish();
}

void RunEngine::CheckWriter() {
  if (auto fatal = writer_->FatalError()) {
    throw Stop{ExitStatus::kFailed, "cannot record frames: " + *fatal};
  }
}

void RunEngine::Backoff(int attempt) {
  const double wait = std::min(options_.retry.max_backoff_s,
                               options_.retry.initial_backoff_s * std::pow(2.0, attempt - 1));
  const auto start = Clock::now();
  std::unique_lock lock(mutex_);
  control_changed_.wait_for(lock, std::chrono::duration<double>(wait),
                            [&] { return abort_reason_.has_value(); });
  if (abort_reason_) throw Stop{ExitStatus::kAborted, *abort_reason_};
  lock.unlock();
  clock_s_ += Since(start);
}

void RunEngine::Fault(int p, const std::string& what, int attempt) {
  ++summary_.retries;
  const std::string message = what + " (attempt " + std::to_string(attempt) + " of " +
                              std::to_string(options_.retry.max_attempts) + "; retrying)";
  store_.LogEvent("warning", p, message);
  SetState(RunState::kFault, message);
}

void RunEngine::MoveAxesOnce(const geometry::AxisPositions& axes) {
  std::vector<std::pair<std::string, double>> targets(axes.begin(), axes.end());
  std::vector<rig::MoveReport> reports(targets.size());
  if (plan_.parallel_moves && targets.size() > 1) {
    std::vector<std::exception_ptr> errors(targets.size());
    std::vector<std::thread> threads;
    for (std::size_t i = 0; i < targets.size(); ++i) {
      threads.emplace_back([&, i] {
        try {
          reports[i] = rig_.axes.at(targets[i].first)->MoveTo(targets[i].second);
        } catch (...) {
          errors[i] = std::current_exception();
        }
      });
    }
    for (std::thread& t : threads) t.join();
    for (const std::exception_ptr& e : errors) {
      if (e) std::rethrow_exception(e);
    }
  } else {
    for (std::size_t i = 0; i < targets.size(); ++i) {
      reports[i] = rig_.axes.at(targets[i].first)->MoveTo(targets[i].second);
    }
  }
  double longest = 0, total = 0;
  for (const rig::MoveReport& r : reports) {
    longest = std::max(longest, r.duration_s);
    total += r.duration_s;
  }
  const double taken = plan_.parallel_moves ? longest : total;
  clock_s_ += taken;
  timing_.moves_s += taken;
  timing_.unavoidable_s += longest;  // independent axes could always move at once
}

void RunEngine::MoveTo(int p) {
  const PlannedPosition& position = plan_.positions[p];
  SetState(RunState::kMoving);
  for (int attempt = 1;; ++attempt) {
    CheckControls();
    try {
      test_hooks::KillPoint(test_hooks::kMoving);
      MoveAxesOnce(position.axes);
      test_hooks::KillPoint(test_hooks::kMoving);
      break;
    } catch (const rig::AxisError& e) {
      StopAxes();
      const auto kind = e.kind();
      const bool recoverable = kind == rig::AxisError::Kind::kAlarm ||
                               kind == rig::AxisError::Kind::kTimeout ||
                               kind == rig::AxisError::Kind::kCommunication;
      if (!recoverable || attempt >= options_.retry.max_attempts) {
        throw Stop{
            ExitStatus::kFailed,
            std::string("axis: ") + e.what() +
                (recoverable ? " (gave up after " + std::to_string(attempt) + " attempts)" : "")};
      }
      Fault(p, std::string("axis: ") + e.what(), attempt);
      Backoff(attempt);
      if (kind == rig::AxisError::Kind::kAlarm) {
        for (auto& [name, axis] : rig_.axes) {
          try {
            if (axis->Status().state == rig::AxisState::kAlarm) {
              axis->ResetAlarm();
              store_.LogEvent("info", p, "axis '" + name + "': alarm reset");
            }
          } catch (const rig::AxisError& reset_error) {
            store_.LogEvent("warning", p, std::string("alarm reset failed: ") + reset_error.what());
          }
        }
      }
      SetState(RunState::kMoving, "retrying the move");
    }
  }
  // Axis readings recorded with every frame of the position: what the drives say now.
  readings_.clear();
  for (auto& [name, axis] : rig_.axes) readings_[name] = axis->Status().position;
  if (plan_.settle_s > 0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(plan_.settle_s));
  }
  clock_s_ += plan_.settle_s;
  timing_.settle_s += plan_.settle_s;
  timing_.unavoidable_s += plan_.settle_s;
}

std::vector<rig::Frame> RunEngine::Shoot(int p, double exposure_s, double* actual_s) {
  bool reopen = false;
  for (int attempt = 1;; ++attempt) {
    CheckControls();
    try {
      if (reopen) {
        const auto start = Clock::now();
        rig_.camera->Reopen();
        clock_s_ += Since(start);
        reopen = false;
        store_.LogEvent("info", p, "camera re-opened");
        SetState(RunState::kAcquiring, "camera back");
      }
      *actual_s = rig_.camera->SetExposure(exposure_s);
      test_hooks::KillPoint(test_hooks::kExposing);
      std::vector<rig::Frame> frames = rig_.camera->Capture();
      test_hooks::KillPoint(test_hooks::kDownloading);
      if (frames.empty()) {
        throw rig::CameraError(rig::CameraError::Kind::kIo, 0, "the shot produced no file");
      }
      double exposure = 0, download = 0;
      for (const rig::Frame& f : frames) {
        exposure = std::max(exposure, f.exposure_duration_s);
        download += f.download_duration_s;
      }
      clock_s_ += exposure + download;
      timing_.exposures_s += exposure;
      timing_.downloads_s += download;
      timing_.unavoidable_s += exposure + download;
      return frames;
    } catch (const rig::CameraError& e) {
      using Kind = rig::CameraError::Kind;
      const bool gone = e.kind() == Kind::kGone || (reopen && e.kind() == Kind::kNotFound);
      if (!(e.recoverable() || gone) || attempt >= options_.retry.max_attempts) {
        throw Stop{ExitStatus::kFailed,
                   std::string("camera: ") + e.what() +
                       (e.recoverable() || gone
                            ? " (gave up after " + std::to_string(attempt) + " attempts)"
                            : "")};
      }
      if (gone) reopen = true;
      Fault(p, std::string("camera: ") + e.what(), attempt);
      Backoff(attempt);
      SetState(RunState::kAcquiring, "retrying the shot");
    }
  }
}

std::vector<double> RunEngine::Meter(int p) {
  double metering = plan_.auto_settings.metering_s;
  for (int tries = 0; tries < 6; ++tries) {
    double actual = 0;
    const std::vector<rig::Frame> frames = Shoot(p, metering, &actual);
    FrameCheckOptions check;
    cv::Mat levels;
    const FrameCheck result =
        CheckFrame(frames.front().bytes, frames.front().file_name, check, &levels);
    if (!result.decoded) {
      throw Stop{ExitStatus::kFailed, "auto-bracketing needs a decodable metering shot, got " +
                                          frames.front().file_name +
                                          "; give explicit exposures in the plan"};
    }
    const MeteringResult m = ChooseBracket(levels, actual, rig_.description.geometry,
                                           plan_.positions[p].axes, plan_.auto_settings);
    if (m.remeter_at_s) {
      metering = *m.remeter_at_s;
      continue;
    }
    std::ostringstream text;
    text << "metering at " << Seconds(actual) << ": highlight " << m.highlight_level << ", paper "
         << m.paper_level << ", sample (median) " << m.sample_level << " of full scale; bracket";
    for (const double e : m.bracket_s) text << " " << Seconds(e);
    store_.LogEvent("info", p, text.str());
    if (m.sample_needs_s) {
      std::ostringstream warning;
      warning << "the sample is dark: it would need " << Seconds(*m.sample_needs_s) << " to reach "
              << plan_.auto_settings.sample_level
              << " of full scale, and the bracket stops at longest_max_s "
              << Seconds(plan_.auto_settings.longest_max_s)
              << "; the reconstruction leaves out what stays below its noise floor (raise "
                 "longest_max_s, or the light)";
      store_.LogEvent("warning", p, warning.str());
    }
    return m.bracket_s;
  }
  throw Stop{ExitStatus::kFailed,
             "auto-bracketing: the highlight stays saturated at the "
             "shortest metering exposure; reduce the light"};
}

void RunEngine::CapturePosition(int p) {
  const double start_clock = clock_s_;
  {
    std::lock_guard lock(mutex_);
    progress_.position = p;
    progress_.frame = 0;
    if (position_model_s_.empty()) progress_.eta_s = estimated_position_s_ * remaining_;
  }
  MoveTo(p);
  SetState(RunState::kAcquiring);
  const std::vector<double> bracket = plan_.auto_bracket ? Meter(p) : plan_.exposures_s;
  for (std::size_t b = 0; b < bracket.size(); ++b) {
    {
      std::lock_guard lock(mutex_);
      progress_.frame = static_cast<int>(b);
    }
    Publish();
    double actual = 0;
    const std::string captured_at = UtcNow();
    std::vector<rig::Frame> frames = Shoot(p, bracket[b], &actual);
    for (std::size_t f = 0; f < frames.size(); ++f) {
      CapturedFrame job;
      job.record.position_index = p;
      job.record.bracket_index = static_cast<int>(b);
      job.record.file_index = static_cast<int>(f);
      job.record.axis_readings = readings_;
      job.record.requested_exposure_s = bracket[b];
      job.record.exposure_s = frames[f].exposure_s > 0 ? frames[f].exposure_s : actual;
      job.record.camera_file_name = frames[f].file_name;
      job.record.captured_at = captured_at;
      job.record.completes_position = b + 1 == bracket.size() && f + 1 == frames.size();
      job.bytes = std::move(frames[f].bytes);
      job.handed_at_s = clock_s_;
      writer_->Push(std::move(job));
    }
    if (!options_.overlap) clock_s_ = std::max(clock_s_, writer_->model_clock_s());
  }
  position_model_s_.push_back(clock_s_ - start_clock);
  ++summary_.positions_done;
}

RunSummary RunEngine::Run(bool resumed) {
  const auto wall_start = Clock::now();
  store_.BeginRun(resumed);
  std::set<int> complete = resumed ? store_.PrepareResume() : store_.CompletePositions();
  {
    std::lock_guard lock(mutex_);
    progress_.frames_recorded = static_cast<int>(complete.size()) * plan_.BracketSize();
  }
  FrameCheckOptions check;
  check.expected_width = rig_.description.geometry.intrinsics.width;
  check.expected_height = rig_.description.geometry.intrinsics.height;
  writer_.emplace(store_, check, options_.overlap, [this](const RecordedInfo& info) {
    {
      std::lock_guard lock(mutex_);
      ++progress_.frames_recorded;
      progress_.last_saturation = info.saturated_fraction;
      ++recorded_this_run_;
    }
    Publish();
  });
  store_.LogEvent("info", -1,
                  std::string(resumed ? "run resumed" : "run started") + ": " +
                      std::to_string(plan_.positions.size() - complete.size()) +
                      " positions to capture");
  std::deque<int> work;
  for (int p = 0; p < static_cast<int>(plan_.positions.size()); ++p) {
    if (!complete.count(p)) work.push_back(p);
  }
  std::map<int, int> redos;
  try {
    if (rig_.light) rig_.light->SetOn(true);
    for (;;) {
      while (!work.empty()) {
        const int p = work.front();
        work.pop_front();
        remaining_ = static_cast<double>(work.size() + 1);
        CapturePosition(p);
        {
          std::lock_guard lock(mutex_);
          double mean = 0;
          for (const double s : position_model_s_) mean += s;
          mean /= static_cast<double>(position_model_s_.size());
          progress_.eta_s = mean * static_cast<double>(work.size());
        }
        CheckWriter();
        if (writer_->HasRejected()) break;
      }
      // Frames that failed their check send their position back to the front of the work.
      clock_s_ = std::max(clock_s_, writer_->model_clock_s());
      const std::set<int> rejected = writer_->TakeRejectedPositions();
      CheckWriter();
      if (rejected.empty() && work.empty()) break;
      for (auto it = rejected.rbegin(); it != rejected.rend(); ++it) {
        if (++redos[*it] > options_.retry.max_position_redos) {
          throw Stop{ExitStatus::kFailed, "position " + std::to_string(*it) +
                                              ": frames keep failing their check (see events)"};
        }
        store_.DiscardPosition(*it);
        ++summary_.redos;
        work.push_front(*it);
      }
    }
    summary_.status = ExitStatus::kSuccess;
  } catch (const Stop& stop) {
    summary_.status = stop.status;
    summary_.reason = stop.reason;
  } catch (const std::exception& e) {
    summary_.status = ExitStatus::kFailed;
    summary_.reason = e.what();
  }
  StopAxes();
  // Whatever was downloaded is still recorded (unless recording itself failed).
  writer_->Drain();
  if (summary_.status == ExitStatus::kSuccess) {
    if (auto fatal = writer_->FatalError()) {
      summary_.status = ExitStatus::kFailed;
      summary_.reason = "cannot record frames: " + *fatal;
    }
  }
  {
    std::lock_guard lock(mutex_);
    summary_.frames_recorded = recorded_this_run_;
  }
  timing_.host_s = writer_->host_s();
  timing_.session_s = std::max(clock_s_, writer_->model_clock_s());
  timing_.wall_s = Since(wall_start);
  summary_.timing = timing_;
  writer_.reset();
  try {
    store_.LogEvent(summary_.status == ExitStatus::kSuccess ? "info" : "error", -1,
                    "run stopped: " + summary_.ToString());
    store_.Stop(summary_.status, summary_.reason);
  } catch (const std::exception& e) {
    // The catalog itself cannot be written (disk full): the run then reads as interrupted,
    // which resumes the same way; the caller still learns why it stopped.
    summary_.status = ExitStatus::kFailed;
    summary_.reason += std::string(summary_.reason.empty() ? "" : "; ") +
                       "cannot write the stop record: " + e.what();
  }
  SetState(RunState::kDone, std::string(ExitStatusName(summary_.status)) +
                                (summary_.reason.empty() ? "" : ": " + summary_.reason));
  return summary_;
}

}  // namespace brdfrig::acquire
