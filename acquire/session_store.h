// The session directory: the catalog session.sqlite (WAL) plus the frames and a snapshot of
// the configuration, written so that a crash at any instant loses nothing that was recorded.
//
//   <session>/session.sqlite   catalog (schema: docs/acquire.md)
//   <session>/plan.yaml        the plan as submitted
//   <session>/rig/             copies of the rig file, its geometry file and scene files
//   <session>/frames/p003_b1.png   position 3, bracket 1 (extension from the camera)
//   <session>/session.lock     flock'ed by the one process writing the session
//
// A frame is written to a temporary name, fsync'ed, renamed, the directory fsync'ed, and only
// then recorded, in one transaction that also marks its position complete when it is the
// position's last frame. A position is the unit of redo: PrepareResume() deletes whatever an
// interrupted run left of incomplete positions (rows, files, temporary files).
// Thread-safe: the run engine logs events while its writer thread records frames.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <mutex>
#include <set>
#include <span>
#include <string>
#include <vector>

#include "acquire/plan.h"
#include "rig/rig_file.h"
#include "session/sqlite_db.h"

namespace brdfrig::acquire {

// Letters, digits, '.', '_', '-'; starts with a letter or digit; at most 100 characters. This
// keeps a name one path component: no '/', no "..", nothing hidden.
bool IsValidSessionName(const std::string& name);
// Throws brdfrig::Error saying what is wrong with the name.
void ValidateSessionName(const std::string& name);

enum class ExitStatus { kSuccess, kAborted, kFailed };
const char* ExitStatusName(ExitStatus status);  // "success", "aborted", "failed"

// One file of one shot, as the engine hands it to the store.
struct FrameToRecord {
  int position_index = 0;
  int bracket_index = 0;
  int file_index = 0;                     // a shot may give several files (RAW + JPEG)
  geometry::AxisPositions axis_readings;  // radians, read back from the drives
  double requested_exposure_s = 0;
  double exposure_s = 0;
  std::string camera_file_name;  // the camera's name (for the extension and the record)
  std::string captured_at;       // UTC, ISO 8601
  double saturated_fraction = 0;
  bool completes_position = false;  // the last file of the position's last shot
};

class SessionStore {
 public:
  // Creates a new session directory (its parent is created if needed). Refuses an existing
  // directory: a session is never overwritten.
  static std::unique_ptr<SessionStore> Create(const std::filesystem::path& dir, const Plan& plan,
                                              const geometry::RigDescription& rig);
  // Opens an existing session to resume it. Throws when another process has it open.
  static std::unique_ptr<SessionStore> Open(const std::filesystem::path& dir);

  ~SessionStore();
  SessionStore(const SessionStore&) = delete;
  SessionStore& operator=(const SessionStore&) = delete;

  const std::filesystem::path& dir() const { return dir_; }
  std::string PlanText();
  std::string PlanSource();

  // Whether a run was ever started (a session created but never run has none).
  bool HasRuns();
  // Starts a run (the first, or a resumption) in the run log.
  void BeginRun(bool resumed);
  // Discards what an interrupted run left of incomplete positions: their rows, their files
  // and any temporary file. Returns the complete positions.
  std::set<int> PrepareResume();
  std::set<int> CompletePositions();
  // Forgets one position's frames (a frame failed its check: the position is redone).
  void DiscardPosition(int position_index);

  // Writes the file durably, then records it (one transaction). Returns the file's name
  // relative to the session directory.
  std::string WriteFrame(const FrameToRecord& frame, std::span<const std::byte> bytes);

  void LogEvent(const std::string& level, int position_index, const std::string& message);
  // Ends the current run with its exit status.
  void Stop(ExitStatus status, const std::string& reason);

  static std::string FrameFileName(int position, int bracket, int file_index,
                                   const std::string& camera_file_name);

 private:
  SessionStore(std::filesystem::path dir, std::unique_ptr<session::SqliteDb> db);
  void DeleteFramesLocked(int position_index);

  std::filesystem::path dir_;
  std::unique_ptr<session::SqliteDb> db_;
  std::mutex mutex_;
  std::int64_t run_id_ = 0;
  int lock_fd_ = -1;  // flock'ed while this store is open
};

// The hidden ".NAME.tmp-PID" directories that a creation killed half-way left in `parent`
// (never sessions: a session is renamed into place only once its start record is committed).
// Those whose process is gone are removed; those of a running process are left alone. Returns
// one line per directory found, saying which.
std::vector<std::string> CleanStaleSessionTemporaries(const std::filesystem::path& parent);

// UTC now, ISO 8601 with milliseconds ("2026-11-29T17:03:17.123Z").
std::string UtcNow();

}  // namespace brdfrig::acquire
