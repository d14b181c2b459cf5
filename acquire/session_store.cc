#include "acquire/session_store.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <nlohmann/json.hpp>

#include "acquire/test_hooks.h"
#include "common/atomic_file.h"
#include "common/sha256.h"
#include "session/catalog_checks.h"
#include "session/rig_snapshot.h"

namespace brdfrig::acquire {

using session::SnapshotFile;
using session::SqliteDb;
using session::Statement;
using session::Transaction;
using session::WriteRigSnapshot;

namespace {

namespace fs = std::filesystem;

// 2: meta holds 'validation_positions' (JSON list of position indices); 1 had no roles.
constexpr int kSchemaVersion = session::kSessionSchemaVersion;

constexpr const char* kSchema = R"sql(
CREATE TABLE meta(key TEXT PRIMARY KEY, value TEXT NOT NULL);
CREATE TABLE session(
  id INTEGER PRIMARY KEY CHECK (id = 1),
  name TEXT NOT NULL, sample TEXT NOT NULL, operator TEXT NOT NULL, notes TEXT NOT NULL,
  software_version TEXT NOT NULL, created_at TEXT NOT NULL,
  plan_source TEXT NOT NULL, plan_text TEXT NOT NULL,
  rig_file TEXT NOT NULL,
  positions_json TEXT NOT NULL, exposures_json TEXT NOT NULL, bracket_size INTEGER NOT NULL);
CREATE TABLE snapshot_files(
  name TEXT PRIMARY KEY, role TEXT NOT NULL, original_path TEXT NOT NULL, sha256 TEXT NOT NULL);
CREATE TABLE runs(
  id INTEGER PRIMARY KEY, started_at TEXT NOT NULL, resumed INTEGER NOT NULL,
  stopped_at TEXT, exit_status TEXT, reason TEXT);
CREATE TABLE frames(
  id INTEGER PRIMARY KEY, run_id INTEGER NOT NULL,
  position_index INTEGER NOT NULL, bracket_index INTEGER NOT NULL, file_index INTEGER NOT NULL,
  axis_readings_json TEXT NOT NULL,
  requested_exposure_s REAL NOT NULL, exposure_s REAL NOT NULL,
  camera_file_name TEXT NOT NULL, file TEXT NOT NULL UNIQUE, sha256 TEXT NOT NULL,
  bytes INTEGER NOT NULL, captured_at TEXT NOT NULL, recorded_at TEXT NOT NULL,
  status TEXT NOT NULL, saturated_fraction REAL NOT NULL,
  UNIQUE (position_index, bracket_index, file_index));
CREATE TABLE positions(
  position_index INTEGER PRIMARY KEY, completed_at TEXT NOT NULL, run_id INTEGER NOT NULL);
CREATE TABLE events(
  id INTEGER PRIMARY KEY, at TEXT NOT NULL, run_id INTEGER, level TEXT NOT NULL,
  position_index INTEGER, message TEXT NOT NULL);
)sql";

[[noreturn]] void ThrowSystem(const std::string& what, const fs::path& path, int err) {
  throw Error(what + " '" + path.string() + "': " + std::strerror(err));
}

bool IsTemporary(const fs::path& file) {
  const std::string name = file.filename().string();
  return name.ends_with(".tmp") || name.find(".tmp-") != std::string::npos;
}

nlohmann::json AxesJson(const geometry::AxisPositions& axes) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, angle] : axes) j[name] = angle;
  return j;
}

}  // namespace

bool IsValidSessionName(const std::string& name) {
  if (name.empty() || name.size() > 100) return false;
  if (!std::isalnum(static_cast<unsigned char>(name[0]))) return false;
  for (const char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') {
      return false;
    }
  }
  return name.find("..") == std::string::npos;
}

void ValidateSessionName(const std::string& name) {
  if (!IsValidSessionName(name)) {
    throw Error("invalid session name '" + name +
                "': use 1-100 letters, digits, '.', '_' or '-', starting with a letter or digit "
                "(no '/', no '..')");
  }
}

const char* ExitStatusName(ExitStatus status) {
  switch (status) {
    case ExitStatus::kSuccess:
      return "success";
    case ExitStatus::kAborted:
      return "aborted";
    case ExitStatus::kFailed:
      return "failed";
  }
  return "failed";
}

std::vector<std::string> CleanStaleSessionTemporaries(const fs::path& parent) {
  std::vector<std::string> found;
  std::error_code error;
  if (!fs::is_directory(parent, error)) return found;
  for (const auto& entry : fs::directory_iterator(parent, error)) {
    const std::string name = entry.path().filename().string();
    const std::size_t tmp = name.rfind(".tmp-");
    if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos || tmp < 2) continue;
    const std::string session = name.substr(1, tmp - 1), pid_text = name.substr(tmp + 5);
    if (!IsValidSessionName(session) || pid_text.empty() || pid_text.size() > 9 ||
        pid_text.find_first_not_of("0123456789") != std::string::npos ||
        !entry.is_directory(error)) {
      continue;
    }
    const pid_t pid = static_cast<pid_t>(std::stol(pid_text));
    const bool alive = pid > 0 && (::kill(pid, 0) == 0 || errno == EPERM);
    if (alive) {
      found.push_back("unfinished session creation " + entry.path().string() + " of pid " +
                      pid_text + " (still running): left alone");
      continue;
    }
    fs::remove_all(entry.path(), error);
    found.push_back(error ? "cannot remove the unfinished session creation " +
                                entry.path().string() + ": " + error.message()
                          : "removed " + entry.path().string() + ", left by pid " + pid_text +
                                " killed while it created session '" + session + "'");
  }
  return found;
}

std::string UtcNow() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms =
      std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char text[96];
  std::snprintf(text, sizeof text, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900,
                tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  return text;
}

SessionStore::SessionStore(fs::path dir, std::unique_ptr<SqliteDb> db)
    : dir_(std::move(dir)), db_(std::move(db)) {}

SessionStore::~SessionStore() {
  db_.reset();
  if (lock_fd_ >= 0) ::close(lock_fd_);
}

std::unique_ptr<SessionStore> SessionStore::Create(const fs::path& final_dir, const Plan& plan,
                                                   const geometry::RigDescription& rig) {
  ValidateSessionName(final_dir.filename().string());
  const fs::path parent = final_dir.parent_path().empty() ? fs::path(".") : final_dir.parent_path();
  fs::create_directories(parent);
  const std::string exists = "cannot create session '" + final_dir.string() +
                             "': it already exists (use --resume to continue it)";
  if (fs::exists(final_dir)) throw Error(exists);
  // Built under a hidden temporary name and renamed when complete, so that a crash during
  // creation never leaves a half-made session under the real name.
  const fs::path dir =
      parent / ("." + final_dir.filename().string() + ".tmp-" + std::to_string(::getpid()));
  fs::remove_all(dir);  // a leftover of this pid; a symlink there is removed, never followed
  // mkdir(2) refuses anything that is there (fs::create_directory accepts a symlink to a
  // directory): the session is built only in a directory this call made.
  if (::mkdir(dir.c_str(), 0777) != 0) ThrowSystem("cannot create session directory", dir, errno);
  // A creation that fails half-way (disk full, an unreadable rig file) leaves nothing behind.
  try {
    fs::create_directory(dir / "frames");
    WriteFileAtomically(dir / "plan.yaml", plan.text);

    // The rig snapshot: every file needed to reprocess the session on its own.
    const std::vector<SnapshotFile> snapshot = WriteRigSnapshot(dir, rig);

    auto db = std::make_unique<SqliteDb>(dir / "session.sqlite", SqliteDb::Mode::kCreate);
    db->Exec("PRAGMA journal_mode=WAL");
    db->Exec("PRAGMA synchronous=FULL");
    Transaction tx(*db);
    db->Exec(kSchema);
    Statement(*db, "INSERT INTO meta VALUES ('schema_version', ?1)")
        .Bind(1, std::to_string(kSchemaVersion))
        .Run();
    nlohmann::json positions = nlohmann::json::array();
    nlohmann::json validation = nlohmann::json::array();
    for (std::size_t i = 0; i < plan.positions.size(); ++i) {
      positions.push_back(AxesJson(plan.positions[i].axes));
      if (plan.positions[i].validation) validation.push_back(i);
    }
    Statement(*db, "INSERT INTO meta VALUES ('validation_positions', ?1)")
        .Bind(1, validation.dump())
        .Run();
    nlohmann::json exposures =
        plan.auto_bracket ? nlohmann::json("auto") : nlohmann::json(plan.exposures_s);
    Statement(*db,
              "INSERT INTO session VALUES (1, ?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)")
        .Bind(1, final_dir.filename().string())
        .Bind(2, plan.sample)
        .Bind(3, plan.operator_name)
        .Bind(4, plan.notes)
        .Bind(5, BRDFRIG_VERSION)
        .Bind(6, UtcNow())
        .Bind(7, plan.file)
        .Bind(8, plan.text)
        .Bind(9, rig.file.string())
        .Bind(10, positions.dump())
        .Bind(11, exposures.dump())
        .Bind(12, plan.BracketSize())
        .Run();
    for (const SnapshotFile& f : snapshot) {
      Statement(*db, "INSERT INTO snapshot_files VALUES (?1, ?2, ?3, ?4)")
          .Bind(1, f.name)
          .Bind(2, f.role)
          .Bind(3, f.original.string())
          .Bind(4, f.sha256)
          .Run();
    }
    tx.Commit();
    db.reset();  // SQLite names its -wal and -shm files by path: close before the rename
    SyncDirectory(dir);
  } catch (...) {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
    throw;
  }
  // rename(2) refuses a non-empty target: a session that appeared meanwhile is kept.
  if (::rename(dir.c_str(), final_dir.c_str()) != 0) {
    const int err = errno;
    fs::remove_all(dir);
    if (err == EEXIST || err == ENOTEMPTY) throw Error(exists);
    ThrowSystem("cannot create session", final_dir, err);
  }
  SyncDirectory(parent);
  return Open(final_dir);
}

std::unique_ptr<SessionStore> SessionStore::Open(const fs::path& dir) {
  if (!fs::exists(dir / "session.sqlite")) {
    throw Error("'" + dir.string() + "' is not a session (no session.sqlite)");
  }
  // One writer per session: a second capture or daemon on the same session would interleave
  // frames. flock() is released by the kernel when the holder dies, so a crash never leaves
  // the session locked.
  const fs::path lock_file = dir / "session.lock";
  const int lock_fd = ::open(lock_file.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (lock_fd < 0) ThrowSystem("cannot open", lock_file, errno);
  if (::flock(lock_fd, LOCK_EX | LOCK_NB) != 0) {
    ::close(lock_fd);
    throw Error("session '" + dir.string() + "' is in use by another capture or the daemon");
  }
  std::unique_ptr<SqliteDb> db;
  try {
    db = std::make_unique<SqliteDb>(dir / "session.sqlite", SqliteDb::Mode::kReadWrite);
  } catch (...) {
    ::close(lock_fd);
    throw;
  }
  auto store = std::unique_ptr<SessionStore>(new SessionStore(dir, std::move(db)));
  store->lock_fd_ = lock_fd;  // released by the destructor, whatever happens below
  // Before anything is written or deleted: a newer catalog is not ours to change, and a
  // path that leaves the session (absolute, "../") would make the resume delete elsewhere.
  session::CheckSchemaVersion(*store->db_, dir);
  session::CheckCatalogPaths(*store->db_, dir);
  store->db_->Exec("PRAGMA synchronous=FULL");
  Statement check(*store->db_, "SELECT COUNT(*) FROM session");
  if (!check.Step() || check.Int(0) != 1) {
    throw Error("'" + dir.string() +
                "' has no start record (its creation was interrupted); "
                "remove it and start again");
  }
  return store;
}

std::string SessionStore::PlanText() {
  std::lock_guard lock(mutex_);
  Statement s(*db_, "SELECT plan_text FROM session");
  s.Step();
  return s.Text(0);
}

std::string SessionStore::PlanSource() {
  std::lock_guard lock(mutex_);
  Statement s(*db_, "SELECT plan_source FROM session");
  s.Step();
  return s.Text(0);
}

bool SessionStore::HasRuns() {
  std::lock_guard lock(mutex_);
  Statement s(*db_, "SELECT COUNT(*) FROM runs");
  s.Step();
  return s.Int(0) > 0;
}

void SessionStore::BeginRun(bool resumed) {
  std::lock_guard lock(mutex_);
  Statement(*db_, "INSERT INTO runs(started_at, resumed) VALUES (?1, ?2)")
      .Bind(1, UtcNow())
      .Bind(2, resumed ? 1 : 0)
      .Run();
  run_id_ = db_->LastInsertId();
}

std::set<int> SessionStore::CompletePositions() {
  std::lock_guard lock(mutex_);
  std::set<int> complete;
  Statement s(*db_, "SELECT position_index FROM positions");
  while (s.Step()) complete.insert(static_cast<int>(s.Int(0)));
  return complete;
}

void SessionStore::DeleteFramesLocked(int position_index) {
  std::vector<std::string> files;
  {
    Statement s(*db_, "SELECT file FROM frames WHERE position_index = ?1");
    s.Bind(1, position_index);
    while (s.Step()) files.push_back(s.Text(0));
  }
  Transaction tx(*db_);
  Statement(*db_, "DELETE FROM frames WHERE position_index = ?1").Bind(1, position_index).Run();
  tx.Commit();
  // Rows first, files second: a crash in between leaves unrecorded files, which the next
  // PrepareResume removes; never a row without its file.
  for (const std::string& f : files)
    fs::remove(session::CatalogFile(dir_, "frames", f, "frames.file"));
}

std::set<int> SessionStore::PrepareResume() {
  std::set<int> complete = CompletePositions();
  std::lock_guard lock(mutex_);
  std::set<int> with_frames;
  {
    Statement s(*db_, "SELECT DISTINCT position_index FROM frames");
    while (s.Step()) with_frames.insert(static_cast<int>(s.Int(0)));
  }
  int discarded = 0;
  for (const int p : with_frames) {
    if (!complete.count(p)) {
      DeleteFramesLocked(p);
      ++discarded;
    }
  }
  // Files nobody recorded: temporaries, and files renamed into place just before a crash.
  std::set<std::string> recorded;
  {
    Statement s(*db_, "SELECT file FROM frames");
    while (s.Step()) recorded.insert(s.Text(0));
  }
  int removed = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "frames")) {
    const std::string rel = "frames/" + entry.path().filename().string();
    if (IsTemporary(entry.path()) || !recorded.count(rel)) {
      fs::remove(entry.path());
      ++removed;
    }
  }
  SyncDirectory(dir_ / "frames");
  Statement(*db_, "INSERT INTO events(at, run_id, level, message) VALUES (?1, ?2, 'info', ?3)")
      .Bind(1, UtcNow())
      .Bind(2, run_id_)
      .Bind(3, "resume: " + std::to_string(complete.size()) + " positions complete, " +
                   std::to_string(discarded) + " incomplete discarded, " + std::to_string(removed) +
                   " unrecorded files removed")
      .Run();
  return complete;
}

void SessionStore::DiscardPosition(int position_index) {
  std::lock_guard lock(mutex_);
  DeleteFramesLocked(position_index);
}

std::string SessionStore::FrameFileName(int position, int bracket, int file_index,
                                        const std::string& camera_file_name) {
  char stem[48];
  if (file_index == 0) {
    std::snprintf(stem, sizeof stem, "p%03d_b%d", position, bracket);
  } else {
    std::snprintf(stem, sizeof stem, "p%03d_b%d_%d", position, bracket, file_index);
  }
  std::string ext = fs::path(camera_file_name).extension().string();
  // The extension comes from the camera: keep it a plain one.
  if (ext.size() > 8 || ext.find_first_of("/\\") != std::string::npos) ext = ".bin";
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return std::string("frames/") + stem + ext;
}

std::string SessionStore::WriteFrame(const FrameToRecord& frame, std::span<const std::byte> bytes) {
  const std::string rel = FrameFileName(frame.position_index, frame.bracket_index, frame.file_index,
                                        frame.camera_file_name);
  const fs::path final_path = dir_ / rel;
  test_hooks::BeforeFrameWrite();
  const fs::path tmp = WriteTemporaryAndSync(final_path, bytes);
  test_hooks::KillPoint(test_hooks::kWriting);
  RenameAndSync(tmp, final_path);
  test_hooks::KillPoint(test_hooks::kRecording);
  const std::string sha = Sha256Hex(bytes);

  std::lock_guard lock(mutex_);
  Transaction tx(*db_);
  Statement(*db_,
            "INSERT INTO frames(run_id, position_index, bracket_index, file_index, "
            "axis_readings_json, requested_exposure_s, exposure_s, camera_file_name, file, sha256, "
            "bytes, captured_at, recorded_at, status, saturated_fraction) VALUES "
            "(?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12, ?13, 'recorded', ?14)")
      .Bind(1, run_id_)
      .Bind(2, frame.position_index)
      .Bind(3, frame.bracket_index)
      .Bind(4, frame.file_index)
      .Bind(5, AxesJson(frame.axis_readings).dump())
      .Bind(6, frame.requested_exposure_s)
      .Bind(7, frame.exposure_s)
      .Bind(8, frame.camera_file_name)
      .Bind(9, rel)
      .Bind(10, sha)
      .Bind(11, static_cast<std::int64_t>(bytes.size()))
      .Bind(12, frame.captured_at)
      .Bind(13, UtcNow())
      .Bind(14, frame.saturated_fraction)
      .Run();
  if (frame.completes_position) {
    Statement(*db_, "INSERT INTO positions VALUES (?1, ?2, ?3)")
        .Bind(1, frame.position_index)
        .Bind(2, UtcNow())
        .Bind(3, run_id_)
        .Run();
  }
  test_hooks::KillPoint(test_hooks::kRecording);  // inside the transaction: must roll back
  tx.Commit();
  test_hooks::KillPoint(test_hooks::kRecording);
  return rel;
}

void SessionStore::LogEvent(const std::string& level, int position_index,
                            const std::string& message) {
  std::lock_guard lock(mutex_);
  Statement s(*db_,
              "INSERT INTO events(at, run_id, level, position_index, message) "
              "VALUES (?1, ?2, ?3, ?4, ?5)");
  s.Bind(1, UtcNow()).Bind(2, run_id_).Bind(3, level).Bind(5, message);
  if (position_index >= 0) {
    s.Bind(4, position_index);
  } else {
    s.BindNull(4);
  }
  s.Run();
}

void SessionStore::Stop(ExitStatus status, const std::string& reason) {
  std::lock_guard lock(mutex_);
  Statement(*db_, "UPDATE runs SET stopped_at = ?1, exit_status = ?2, reason = ?3 WHERE id = ?4")
      .Bind(1, UtcNow())
      .Bind(2, ExitStatusName(status))
      .Bind(3, reason)
      .Bind(4, run_id_)
      .Run();
}

}  // namespace brdfrig::acquire
