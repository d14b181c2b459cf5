// The acquisition daemon (`brdfrig daemon`): owns the rig, keeps a queue of submitted plans,
// runs them one at a time with the run engine, and answers a JSON control API (HTTP over a
// Unix domain socket with mode 0600, optionally loopback TCP with a bearer token). Sessions
// are created only as <data_dir>/<validated name>: nothing a client sends names a path.
//
//   GET  /v1/status                     state, running session, progress, queue, last result
//   GET  /v1/sessions                   every session in data_dir, the queue, resumable ones
//   POST /v1/sessions                   {"name": "...", "plan": "<plan.yaml text>"} → 201
//                                       (the session directory is created at once)
//   POST /v1/sessions/NAME/resume       queue an interrupted/failed/aborted session → 202
//   POST /v1/pause | /v1/resume         the running session (409 when none)
//   POST /v1/abort                      {"reason": "..."} optional (409 when none)
// Errors: {"error": "why"} with 400 (malformed request, bad plan with file:line), 401 (token),
// 404, 405, 409 (name taken, nothing running, ...), 413 (body over 1 MiB).
//
// On start it lists sessions a crash interrupted and, when configured, queues their resume.
// After each session that completes it runs the configured hand-off command (capture → fit
// unattended; acquire/hand_off.h).
// Logs go to stderr, one line per event (journald adds the time).
#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "acquire/daemon_config.h"
#include "acquire/http_server.h"
#include "acquire/plan.h"
#include "acquire/run_engine.h"
#include "common/file_lock.h"
#include "rig/rig_file.h"

namespace brdfrig::acquire {

class Daemon {
 public:
  // Locks data_dir and the rig (a second daemon or a capture on either fails here, naming
  // the holder, before any device is opened), opens the rig, scans data_dir, starts listening and
  // the runner. Throws brdfrig::Error.
  explicit Daemon(DaemonConfig config);
  // Aborts a running session ("daemon stopped"; resumable), ends running hand-offs (logged with
  // their command), stops listening, removes the socket.
  ~Daemon();
  Daemon(const Daemon&) = delete;
  Daemon& operator=(const Daemon&) = delete;

  int tcp_port() const { return tcp_port_; }
  const DaemonConfig& config() const { return config_; }
  // Blocks until the queue is empty and nothing runs, hand-offs included (for tests).
  void WaitIdle();

  HttpResponse Handle(const HttpRequest& request);

 private:
  // A queued session. Its directory exists from submission on (the plan is stored there), so
  // a queue survives a restart: a session never started reads as resumable.
  struct Job {
    std::string name;
  };

  HttpResponse Status();
  HttpResponse ListSessions();
  HttpResponse Submit(const std::string& body);
  HttpResponse ResumeSession(const std::string& name);
  HttpResponse Control(const std::string& action, const std::string& body);
  bool KnownLocked(const std::string& name) const;
  void RunnerLoop();
  void RunJob(const Job& job);
  // Runs the configured hand-off command for a completed session (acquire/hand_off.h).
  void StartHandOff(const std::string& name);
  void Log(const std::string& line);

  DaemonConfig config_;
  FileLock data_dir_lock_;  // one daemon per data directory
  rig::Rig rig_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  std::string running_;          // name of the running session ("" when idle)
  RunEngine* engine_ = nullptr;  // the running session's engine, under mutex_
  std::optional<RunProgress> progress_;
  std::string last_result_;  // one line about the last finished run
  bool stopping_ = false;
  std::mutex log_mutex_;
  std::thread runner_;
  std::vector<std::thread> hand_offs_;  // under mutex_; joined on destruction
  int hand_offs_running_ = 0;           // under mutex_
  // Set on destruction: hand-offs still running are ended, so that stopping never waits for
  // a lab's command (acquire/hand_off.h).
  std::atomic<bool> stop_hand_offs_{false};
  std::unique_ptr<HttpServer> unix_server_;
  std::unique_ptr<HttpServer> tcp_server_;
  int tcp_port_ = 0;
};

// `brdfrig daemon`: runs until SIGINT or SIGTERM.
void ServeUntilSignal(const DaemonConfig& config);

}  // namespace brdfrig::acquire
