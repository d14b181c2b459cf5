// The run engine's writer: checks each captured frame (frame_check.h) and records it in the
// session store, on its own thread so that the recording of position k overlaps the move to
// k+1 (or inline, for the serial comparison). It keeps the writer's side of the engine's
// session-time model: each job starts when both the writer is free and the frame exists
// (model time), and takes the host time it really took.
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "acquire/frame_check.h"
#include "acquire/session_store.h"

namespace brdfrig::acquire {

struct CapturedFrame {
  FrameToRecord record;
  std::vector<std::byte> bytes;
  double handed_at_s = 0;  // engine model time when the frame was downloaded
};

struct RecordedInfo {
  int position_index = 0;
  int bracket_index = 0;
  double saturated_fraction = 0;
  bool position_complete = false;
};

class FrameWriter {
 public:
  using OnRecorded = std::function<void(const RecordedInfo&)>;
  FrameWriter(SessionStore& store, FrameCheckOptions check, bool threaded, OnRecorded on_recorded);
  ~FrameWriter();
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // Threaded: queues the job (blocks while `max_pending` jobs wait). Inline: does it now.
  void Push(CapturedFrame job);
  // Waits until every pushed job is done.
  void Drain();
  // A write failure (disk full, I/O error) stops all further recording; the message says why.
  std::optional<std::string> FatalError();
  // Whether a frame failed its check since the last TakeRejectedPositions.
  bool HasRejected();
  // Drains, then returns the positions one of whose frames failed its check (their later
  // frames were not recorded) and forgets them, so that their redo is recorded afresh.
  std::set<int> TakeRejectedPositions();
  // Model time at which the writer finishes its last job, and the host time it spent.
  double model_clock_s();
  double host_s();

  static constexpr std::size_t kMaxPending = 12;

 private:
  void Loop();
  void Process(CapturedFrame& job);

  SessionStore& store_;
  FrameCheckOptions check_;
  bool threaded_;
  OnRecorded on_recorded_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<CapturedFrame> queue_;
  bool busy_ = false;
  bool stopping_ = false;
  std::optional<std::string> fatal_;
  // Positions rejected since the last TakeRejectedPositions: their remaining frames are skipped.
  std::set<int> rejected_;
  double clock_s_ = 0;
  double host_s_ = 0;
  std::thread thread_;
};

}  // namespace brdfrig::acquire
