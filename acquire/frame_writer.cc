#include "acquire/frame_writer.h"

#include <chrono>

namespace brdfrig::acquire {

FrameWriter::FrameWriter(SessionStore& store, FrameCheckOptions check, bool threaded,
                         OnRecorded on_recorded)
    : store_(store), check_(check), threaded_(threaded), on_recorded_(std::move(on_recorded)) {
  if (threaded_) thread_ = std::thread([this] { Loop(); });
}

FrameWriter::~FrameWriter() {
  if (threaded_) {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
}

void FrameWriter::Push(CapturedFrame job) {
  if (!threaded_) {
    Process(job);
    return;
  }
  std::unique_lock lock(mutex_);
  // Bounded: a slow disk holds the engine back instead of filling memory with frames.
  changed_.wait(lock, [&] { return queue_.size() < kMaxPending; });
  queue_.push_back(std::move(job));
  changed_.notify_all();
}

void FrameWriter::Drain() {
  if (!threaded_) return;
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.empty() && !busy_; });
}

std::optional<std::string> FrameWriter::FatalError() {
  std::lock_guard lock(mutex_);
  return fatal_;
}

bool FrameWriter::HasRejected() {
  std::lock_guard lock(mutex_);
  return !rejected_.empty();
}

std::set<int> FrameWriter::TakeRejectedPositions() {
  Drain();
  std::lock_guard lock(mutex_);
  // A position taken for redo gets recorded again from scratch.
  std::set<int> rejected;
  rejected.swap(rejected_);
  return rejected;
}

double FrameWriter::model_clock_s() {
  std::lock_guard lock(mutex_);
  return clock_s_;
}

double FrameWriter::host_s() {
  std::lock_guard lock(mutex_);
  return host_s_;
}

void FrameWriter::Loop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) return;  // stopping, and nothing left to record
    CapturedFrame job = std::move(queue_.front());
    queue_.pop_front();
    busy_ = true;
    changed_.notify_all();
    lock.unlock();
    Process(job);
    lock.lock();
    busy_ = false;
    changed_.notify_all();
  }
}

void FrameWriter::Process(CapturedFrame& job) {
  const int position = job.record.position_index;
  {
    std::lock_guard lock(mutex_);
    if (fatal_ || rejected_.count(position)) return;
  }
  const auto start = std::chrono::steady_clock::now();
  RecordedInfo info;
  info.position_index = position;
  info.bracket_index = job.record.bracket_index;
  info.position_complete = job.record.completes_position;
  std::optional<std::string> fatal;
  bool rejected = false;
  try {
    const FrameCheck check = CheckFrame(job.bytes, job.record.camera_file_name, check_);
    job.record.saturated_fraction = check.saturated_fraction;
    info.saturated_fraction = check.saturated_fraction;
    if (!check.ok) {
      rejected = true;
      store_.LogEvent("error", position,
                      "frame " + std::to_string(job.record.bracket_index) + " (" +
                          job.record.camera_file_name + ") rejected: " + check.problem +
                          "; the position will be redone");
    } else {
      store_.WriteFrame(job.record, job.bytes);
    }
  } catch (const std::exception& e) {
    fatal = e.what();
  }
  const double host =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  {
    std::lock_guard lock(mutex_);
    clock_s_ = std::max(clock_s_, job.handed_at_s) + host;
    host_s_ += host;
    if (fatal) fatal_ = fatal;
    if (rejected) {
      rejected_.insert(position);
    }
  }
  if (!fatal && !rejected && on_recorded_) on_recorded_(info);
}

}  // namespace brdfrig::acquire
