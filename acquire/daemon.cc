#include "acquire/daemon.h"

#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "acquire/local_socket.h"
#include "acquire/plan_check.h"
#include "acquire/progress_json.h"
#include "acquire/session_store.h"
#include "common/json_parse.h"
#include "session/session_reader.h"

namespace brdfrig::acquire {

using session::ReadSession;
using session::SessionContents;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kDaemonStopped = "daemon stopped";

// Messages may quote what a client sent (a JSON parser's error shows the offending bytes):
// invalid UTF-8 is replaced rather than thrown, so a malformed request still gets its 4xx.
HttpResponse Json(int status, const json& body) {
  return {status, body.dump(-1, ' ', false, json::error_handler_t::replace)};
}
HttpResponse Fail(int status, const std::string& reason) {
  return Json(status, json{{"error", reason}});
}

// Whether a stopped session should be offered (or automatically given) a resume.
bool Interrupted(const SessionContents& s) {
  return s.exit_status == "interrupted" || s.exit_status.empty() ||
         (s.exit_status == "aborted" && s.stop_reason == kDaemonStopped);
}

}  // namespace

Daemon::Daemon(DaemonConfig config) : config_(std::move(config)) {
  config_.Validate();
  fs::create_directories(config_.data_dir);
  // Beside the rig's locks, not in data_dir (which holds sessions only), keyed by the
  // directory's real path so that two spellings of it conflict.
  data_dir_lock_ =
      FileLock::Acquire(rig::LockFile("data", fs::canonical(config_.data_dir).string()),
                        "the data directory " + config_.data_dir.string());
  rig_ = rig::OpenRig(config_.rig_file);
  Log("rig " + config_.rig_file.string() + " open; sessions in " + config_.data_dir.string());
  for (const std::string& line : CleanStaleSessionTemporaries(config_.data_dir)) Log(line);
  // Oldest first (plan.yaml is written when a session is created): the queue keeps its order.
  std::vector<std::pair<fs::file_time_type, fs::path>> found;
  for (const auto& entry : fs::directory_iterator(config_.data_dir)) {
    if (entry.is_directory() && IsValidSessionName(entry.path().filename().string()) &&
        fs::exists(entry.path() / "session.sqlite") && fs::exists(entry.path() / "plan.yaml")) {
      found.emplace_back(fs::last_write_time(entry.path() / "plan.yaml"), entry.path());
    }
  }
  std::sort(found.begin(), found.end());
  for (const auto& [time, path] : found) {
    const std::string name = path.filename().string();
    try {
      const SessionContents s = ReadSession(path);
      if (!Interrupted(s) || s.Complete()) continue;
      if (config_.resume_interrupted) {
        queue_.push_back({name});
        Log("session " + name + " was interrupted: queued for resume");
      } else {
        Log("session " + name + " was interrupted: resumable (POST /v1/sessions/" + name +
            "/resume or `brdfrig resume --session " + name + "`)");
      }
    } catch (const std::exception& e) {
      Log("session " + name + " cannot be read: " + e.what());
    }
  }
  // Sockets first: a daemon that cannot listen (another one runs) must fail before it
  // touches a session.
  const int unix_fd = ListenUnixSocket(config_.socket);
  int tcp_fd = -1;
  if (config_.tcp_port != 0) {
    try {
      tcp_fd = ListenLoopbackTcp(config_.tcp_port);
    } catch (...) {
      ::close(unix_fd);
      ::unlink(config_.socket.c_str());
      throw;
    }
    tcp_port_ = BoundPort(tcp_fd);
  }
  auto handler = [this](const HttpRequest& r) { return Handle(r); };
  unix_server_ = std::make_unique<HttpServer>(unix_fd, handler);
  Log("listening on " + config_.socket.string() + " (mode 0600)");
  if (tcp_fd >= 0) {
    tcp_server_ = std::make_unique<HttpServer>(tcp_fd, handler, config_.token);
    Log("listening on 127.0.0.1:" + std::to_string(tcp_port_) + " (bearer token)");
  }
  runner_ = std::thread([this] { RunnerLoop(); });
}

Daemon::~Daemon() {
  unix_server_.reset();
  tcp_server_.reset();
  ::unlink(config_.socket.c_str());
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
    if (engine_) engine_->Abort(kDaemonStopped);
    changed_.notify_all();
  }
  runner_.join();
  // The runner is gone: nothing adds a hand-off any more.
  stop_hand_offs_ = true;
  for (std::thread& hand_off : hand_offs_) hand_off.join();
  Log("stopped");
}

void Daemon::Log(const std::string& line) {
  std::lock_guard lock(log_mutex_);
  std::fprintf(stderr, "brdfrig-daemon: %s\n", line.c_str());
  std::fflush(stderr);
}

void Daemon::WaitIdle() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock,
                [&] { return queue_.empty() && running_.empty() && hand_offs_running_ == 0; });
}

void Daemon::RunnerLoop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    changed_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    Job job = std::move(queue_.front());
    queue_.pop_front();
    running_ = job.name;
    progress_.reset();
    lock.unlock();
    RunJob(job);
    lock.lock();
    running_.clear();
    engine_ = nullptr;
    changed_.notify_all();
  }
}

void Daemon::RunJob(const Job& job) {
  const fs::path dir = config_.data_dir / job.name;
  std::string result;
  try {
    std::unique_ptr<SessionStore> store = SessionStore::Open(dir);
    Plan plan = LoadPlanString(store->PlanText(), store->PlanSource());
    ResolvePlan(&plan, rig_.description.geometry);
    const bool resumed = store->HasRuns();
    Log("session " + job.name + (resumed ? ": resumed" : ": started"));
    RunState last_state = RunState::kIdle;
    RunEngine engine(rig_, *store, plan, config_.run, [&](const RunProgress& p) {
      if (p.state != last_state) {
        last_state = p.state;
        Log("session " + job.name + ": " + RunStateName(p.state) + " (position " +
            std::to_string(p.position + 1) + "/" + std::to_string(p.positions) + ")" +
            (p.message.empty() ? "" : ": " + p.message));
      }
      std::lock_guard lock(mutex_);
      progress_ = p;
    });
    {
      std::lock_guard lock(mutex_);
      engine_ = &engine;
      if (stopping_) engine.Abort(kDaemonStopped);
    }
    const RunSummary summary = engine.Run(resumed);
    {
      std::lock_guard lock(mutex_);
      engine_ = nullptr;
      progress_ = engine.Progress();
    }
    result = "session " + job.name + ": " + summary.ToString();
    if (summary.status == ExitStatus::kSuccess && config_.hand_off.enabled()) {
      StartHandOff(job.name);
    }
  } catch (const std::exception& e) {
    std::lock_guard lock(mutex_);
    engine_ = nullptr;
    result = "session " + job.name + " could not run: " + e.what();
  }
  Log(result);
  std::lock_guard lock(mutex_);
  last_result_ = result;
}

void Daemon::StartHandOff(const std::string& name) {
  std::lock_guard lock(mutex_);
  ++hand_offs_running_;
  // On a thread of its own: the next session starts while the fit is handed over (a
  // scheduler's sbatch answers in a second, a lab's own command may take longer).
  hand_offs_.emplace_back([this, name] {
    std::string line;
    try {
      line = RunHandOff(config_.hand_off, config_.data_dir / name, name, &stop_hand_offs_);
    } catch (const std::exception& e) {
      line = "session " + name + " could not be handed off: " + e.what();
    }
    Log(line);
    std::lock_guard done(mutex_);
    --hand_offs_running_;
    changed_.notify_all();
  });
}

bool Daemon::KnownLocked(const std::string& name) const {
  if (running_ == name) return true;
  for (const Job& j : queue_) {
    if (j.name == name) return true;
  }
  return false;
}

HttpResponse Daemon::Handle(const HttpRequest& request) {
  const std::string& path = request.path;
  const bool get = request.method == "GET", post = request.method == "POST";
  if (path == "/v1/status") return get ? Status() : Fail(405, "use GET");
  if (path == "/v1/sessions") {
    if (get) return ListSessions();
    if (post) return Submit(request.body);
    return Fail(405, "use GET or POST");
  }
  if (path == "/v1/pause" || path == "/v1/resume" || path == "/v1/abort") {
    return post ? Control(path.substr(4), request.body) : Fail(405, "use POST");
  }
  const std::string prefix = "/v1/sessions/", suffix = "/resume";
  if (path.starts_with(prefix) && path.ends_with(suffix) &&
      path.size() > prefix.size() + suffix.size()) {
    if (!post) return Fail(405, "use POST");
    return ResumeSession(path.substr(prefix.size(), path.size() - prefix.size() - suffix.size()));
  }
  return Fail(404, "no such endpoint: " + request.method + " " + path);
}

HttpResponse Daemon::Status() {
  std::lock_guard lock(mutex_);
  json queue = json::array();
  for (const Job& j : queue_) queue.push_back(j.name);
  json body{{"state", running_.empty() ? "idle" : "running"},
            {"session", running_.empty() ? json() : json(running_)},
            {"queue", queue},
            {"last_result", last_result_}};
  if (progress_) body["progress"] = ProgressToJson(*progress_);
  return Json(200, body);
}

HttpResponse Daemon::ListSessions() {
  std::vector<std::string> queued;
  std::string running;
  {
    std::lock_guard lock(mutex_);
    for (const Job& j : queue_) queued.push_back(j.name);
    running = running_;
  }
  json sessions = json::array();
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(config_.data_dir)) {
    if (entry.is_directory() && IsValidSessionName(entry.path().filename().string()) &&
        fs::exists(entry.path() / "session.sqlite")) {
      dirs.push_back(entry.path());
    }
  }
  std::sort(dirs.begin(), dirs.end());
  for (const fs::path& dir : dirs) {
    const std::string name = dir.filename().string();
    try {
      const SessionContents s = ReadSession(dir);
      const bool busy =
          name == running || std::find(queued.begin(), queued.end(), name) != queued.end();
      sessions.push_back(json{{"name", name},
                              {"sample", s.sample},
                              {"operator", s.operator_name},
                              {"exit_status", name == running ? "running"
                                              : busy          ? "queued"
                                                              : s.exit_status},
                              {"reason", s.stop_reason},
                              {"frames", s.frames.size()},
                              {"complete", s.Complete()},
                              {"resumable", !busy && !s.Complete()}});
    } catch (const std::exception& e) {
      sessions.push_back(json{{"name", name}, {"error", e.what()}});
    }
  }
  return Json(200, json{{"sessions", sessions},
                        {"queue", queued},
                        {"running", running.empty() ? json() : json(running)}});
}

HttpResponse Daemon::Submit(const std::string& body) {
  json request;
  try {
    request = ParseJson(body, "request body");
  } catch (const FileError& e) {
    return Fail(400, e.what());
  }
  if (!request.is_object() || !request.contains("name") || !request["name"].is_string() ||
      !request.contains("plan") || !request["plan"].is_string()) {
    return Fail(400, "expected {\"name\": \"session name\", \"plan\": \"plan.yaml text\"}");
  }
  for (const auto& item : request.items()) {
    if (item.key() != "name" && item.key() != "plan") {
      return Fail(400, "unknown field '" + item.key() + "'");
    }
  }
  const std::string name = request["name"];
  if (!IsValidSessionName(name)) {
    return Fail(400,
                "invalid session name: use 1-100 letters, digits, '.', '_' or '-', "
                "starting with a letter or digit");
  }
  Plan plan;
  json warnings = json::array();
  try {
    plan = LoadPlanString(request["plan"].get<std::string>(), "plan of " + name);
    ResolvePlan(&plan, rig_.description.geometry);
    const PlanCheckReport check = CheckPlan(plan, rig_.description);
    for (const std::string& w : check.warnings) warnings.push_back(w);
    if (!check.ok()) {
      std::string reason = "the plan cannot run on this rig:";
      for (const std::string& e : check.errors) reason += " " + e + ";";
      return Fail(400, reason);
    }
  } catch (const Error& e) {
    return Fail(400, e.what());
  }
  std::lock_guard lock(mutex_);
  if (KnownLocked(name) || fs::exists(config_.data_dir / name)) {
    return Fail(409, "a session named '" + name + "' already exists");
  }
  try {
    SessionStore::Create(config_.data_dir / name, plan, rig_.description);
  } catch (const Error& e) {
    // The name was checked free above: this is the daemon's disk or rig files, not a conflict.
    return Fail(500, std::string("cannot create the session: ") + e.what());
  }
  queue_.push_back({name});
  const int place = static_cast<int>(queue_.size()) + (running_.empty() ? 0 : 1);
  changed_.notify_all();
  Log("session " + name + " submitted (place " + std::to_string(place) + ")");
  return Json(201, json{{"name", name}, {"place", place}, {"warnings", warnings}});
}

HttpResponse Daemon::ResumeSession(const std::string& name) {
  if (!IsValidSessionName(name)) return Fail(400, "invalid session name");
  const fs::path dir = config_.data_dir / name;
  if (!fs::exists(dir / "session.sqlite")) return Fail(404, "no session named '" + name + "'");
  try {
    if (ReadSession(dir).Complete()) return Fail(409, "session '" + name + "' is complete");
  } catch (const std::exception& e) {
    return Fail(409, std::string("session cannot be read: ") + e.what());
  }
  std::lock_guard lock(mutex_);
  if (KnownLocked(name)) return Fail(409, "session '" + name + "' is already queued or running");
  queue_.push_back({name});
  changed_.notify_all();
  Log("session " + name + " queued for resume");
  return Json(202, json{{"name", name}, {"place", queue_.size() + (running_.empty() ? 0 : 1)}});
}

HttpResponse Daemon::Control(const std::string& action, const std::string& body) {
  std::string reason = "aborted by the operator";
  if (action == "abort" && !body.empty()) {
    try {
      const json request = ParseJson(body, "request body");
      if (!request.is_object()) return Fail(400, "expected a JSON object");
      if (request.contains("reason")) {
        if (!request["reason"].is_string()) return Fail(400, "reason must be a string");
        reason = request["reason"];
      }
    } catch (const FileError& e) {
      return Fail(400, e.what());
    }
  }
  std::lock_guard lock(mutex_);
  if (!engine_) return Fail(409, "no session is running");
  if (action == "pause") engine_->Pause();
  if (action == "resume") engine_->Resume();
  if (action == "abort") engine_->Abort(reason);
  Log("session " + running_ + ": " + action + " requested");
  return Json(200, json{{"session", running_}, {"requested", action}});
}

void ServeUntilSignal(const DaemonConfig& config) {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  // Blocked before any thread starts, so that only sigwait below sees them.
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  signal(SIGPIPE, SIG_IGN);  // a client gone mid-response must not kill the daemon
  Daemon daemon(config);
  int sig = 0;
  sigwait(&set, &sig);
  std::fprintf(stderr, "brdfrig-daemon: %s received, shutting down\n",
               sig == SIGINT ? "SIGINT" : "SIGTERM");
}

}  // namespace brdfrig::acquire
