// The daemon's control API over its real Unix socket (and loopback TCP with a token): submit,
// progress, pause, resume, abort, malformed requests, a second client, a client that goes
// away, the socket's permission, and resuming interrupted sessions after a restart.
#include "acquire/daemon.h"

#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "acquire/daemon_client.h"
#include "acquire/local_socket.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {

using session::ReadSession;
using session::SessionContents;
using session::VerifySession;

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Devices sleep 4% of their virtual durations: a 3-position session takes about half a
// second of real time, long enough to pause and abort it through the API.
std::string SlowScene() {
  std::string scene = testing::SmallSceneYaml();
  scene.replace(scene.find("reopen_s: 2"), 11, "reopen_s: 2\n  real_time_factor: 0.04");
  return scene;
}

std::string LongPlan() {
  return "sample: long\npositions: {symmetric_arms: {from_deg: 15, to_deg: 65, count: 8}}\n"
         "exposures: [0.001, 0.01]\nsettle_s: 0\n";
}

class DaemonTest : public ::testing::Test {
 protected:
  void SetUp() override {
    rig_ = testing::MakeTestRig(::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::ofstream(rig_.dir / "scene.yaml") << SlowScene();
    config_.data_dir = rig_.dir / "data";
    config_.rig_file = rig_.rig_file;
    // sun_path holds 107 bytes: the socket lives in a short, unique directory of its own.
    char socket_dir[] = "/tmp/brdfrig-sock-XXXXXX";
    ASSERT_NE(::mkdtemp(socket_dir), nullptr);
    socket_dir_ = socket_dir;
    config_.socket = socket_dir_ / "d.sock";
    config_.run.retry.initial_backoff_s = 0.001;
  }

  void TearDown() override {
    if (!socket_dir_.empty()) fs::remove_all(socket_dir_);
  }

  DaemonClient Client() { return DaemonClient(config_.socket); }

  // Polls the status until `done` holds (or fails the test after 10 s).
  json WaitForStatus(const std::function<bool(const json&)>& done) {
    DaemonClient client = Client();
    for (int i = 0; i < 1000; ++i) {
      const json status = client.Status();
      if (done(status)) return status;
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    ADD_FAILURE() << "status never reached the expected state";
    return client.Status();
  }

  static std::string ProgressState(const json& status) {
    return status.contains("progress") ? status["progress"]["state"].get<std::string>() : "";
  }

  testing::TestRig rig_;
  DaemonConfig config_;
  fs::path socket_dir_;
};

TEST_F(DaemonTest, SocketIsASocketOnlyItsOwnerCanUse) {
  Daemon daemon(config_);
  struct stat st {};
  ASSERT_EQ(::stat(config_.socket.c_str(), &st), 0);
  EXPECT_TRUE(S_ISSOCK(st.st_mode));
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  // A second daemon on the same socket is refused rather than stealing it.
  EXPECT_THROW(Daemon second(config_), Error);
}

TEST_F(DaemonTest, SubmittedPlanRunsToCompletionWithProgress) {
  Daemon daemon(config_);
  DaemonClient client = Client();
  const json submitted = client.Submit("first", testing::SmallPlanYaml());
  EXPECT_EQ(submitted["name"], "first");
  const json running = WaitForStatus([](const json& s) { return s.contains("progress"); });
  EXPECT_EQ(running["progress"]["positions"], 3);
  EXPECT_EQ(running["progress"]["frames_total"], 6);
  daemon.WaitIdle();
  const json status = client.Status();
  EXPECT_EQ(status["state"], "idle");
  EXPECT_EQ(status["progress"]["state"], "done");
  EXPECT_EQ(status["progress"]["frames_recorded"], 6);
  EXPECT_GE(status["progress"]["last_saturation"].get<double>(), 0);
  const json sessions = client.Sessions();
  ASSERT_EQ(sessions["sessions"].size(), 1u);
  EXPECT_EQ(sessions["sessions"][0]["name"], "first");
  EXPECT_EQ(sessions["sessions"][0]["exit_status"], "success");
  EXPECT_EQ(sessions["sessions"][0]["complete"], true);
  EXPECT_EQ(ReadSession(config_.data_dir / "first").frames.size(), 6u);
  EXPECT_TRUE(VerifySession(config_.data_dir / "first").ok());
}

TEST_F(DaemonTest, PauseHoldsResumeContinuesAbortStopsAndTheSessionCanBeResumed) {
  Daemon daemon(config_);
  DaemonClient client = Client();
  client.Submit("long", LongPlan());
  WaitForStatus([](const json& s) {
    return s.contains("progress") && s["progress"]["frames_recorded"].get<int>() >= 2;
  });
  client.Pause();
  const json paused = WaitForStatus([](const json& s) { return ProgressState(s) == "paused"; });
  const int frames_when_paused = paused["progress"]["frames_recorded"];
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(client.Status()["progress"]["frames_recorded"], frames_when_paused);
  EXPECT_EQ(client.Status()["progress"]["state"], "paused");

  client.Resume();
  WaitForStatus([&](const json& s) {
    return s["progress"]["frames_recorded"].get<int>() > frames_when_paused;
  });
  client.Abort("test abort");
  daemon.WaitIdle();
  const SessionContents aborted = ReadSession(config_.data_dir / "long");
  EXPECT_EQ(aborted.exit_status, "aborted");
  EXPECT_EQ(aborted.stop_reason, "test abort");
  EXPECT_FALSE(aborted.Complete());
  EXPECT_TRUE(VerifySession(config_.data_dir / "long").ok());
  EXPECT_EQ(client.Sessions()["sessions"][0]["resumable"], true);

  EXPECT_EQ(client.Request("POST", "/v1/sessions/long/resume").status, 202);
  daemon.WaitIdle();
  const SessionContents resumed = ReadSession(config_.data_dir / "long");
  EXPECT_EQ(resumed.exit_status, "success");
  EXPECT_TRUE(resumed.Complete());
  EXPECT_EQ(resumed.frames.size(), 16u);
  EXPECT_TRUE(VerifySession(config_.data_dir / "long").ok());
}

TEST_F(DaemonTest, CompleteSessionsAreHandedToTheConfiguredCommandAbortedOnesAreNot) {
  const fs::path handed = rig_.dir / "handed.txt";
  config_.hand_off.command = {
      "/bin/sh", "-c",        "printf '%s %s\\n' \"$1\" \"$2\" >> " + handed.string(),
      "sh",      "{session}", "{name}"};
  Daemon daemon(config_);
  DaemonClient client = Client();
  client.Submit("first", testing::SmallPlanYaml());
  daemon.WaitIdle();
  client.Submit("long", LongPlan());
  // The finished first session's progress stays in the status until "long" starts, so the
  // wait names the session: aborting before it runs would answer 409.
  WaitForStatus([](const json& s) {
    return s["session"] == "long" && s.contains("progress") && s["progress"]["state"] != "done" &&
           s["progress"]["frames_recorded"].get<int>() >= 2;
  });
  client.Abort("test abort");
  daemon.WaitIdle();
  ASSERT_TRUE(fs::exists(handed));
  std::ifstream in(handed);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text,
            fs::absolute(config_.data_dir / "first").lexically_normal().string() + " first\n");
}

// Issue 25, finding 10: stopping the daemon waited for a running hand-off however long it took.
TEST_F(DaemonTest, StoppingTheDaemonEndsARunningHandOff) {
  const fs::path started = rig_.dir / "hand_off_started";
  config_.hand_off.command = {"/bin/sh",        "-c",    "touch \"$1\"; sleep 20", "sh",
                              started.string(), "{name}"};
  auto daemon = std::make_unique<Daemon>(config_);
  Client().Submit("first", testing::SmallPlanYaml());
  for (int i = 0; i < 1000 && !fs::exists(started); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(fs::exists(started)) << "the hand-off never ran";
  const auto start = std::chrono::steady_clock::now();
  daemon.reset();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
            kHandOffGraceS + 2);
}

TEST(DaemonConfigTest, HandOffIsReadFromDaemonYamlAndMustNameAnAbsoluteProgramAndTheSession) {
  const fs::path dir = fs::temp_directory_path() / "daemon_config_hand_off";
  fs::create_directories(dir);
  const std::string common = "data_dir: data\nrig: rig.yaml\n";
  std::ofstream(dir / "good.yaml")
      << common << "hand_off:\n  command: [/usr/bin/brdfrig, batch, prepare, \"{session}\"]\n";
  const DaemonConfig config = LoadDaemonConfig(dir / "good.yaml");
  EXPECT_EQ(HandOffCommand(config.hand_off, "/srv/data/s1", "s1"),
            (std::vector<std::string>{"/usr/bin/brdfrig", "batch", "prepare", "/srv/data/s1"}));
  std::ofstream(dir / "relative.yaml") << common << "hand_off: {command: [brdfrig, \"{name}\"]}\n";
  try {
    LoadDaemonConfig(dir / "relative.yaml");
    ADD_FAILURE() << "a relative program was accepted";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("relative.yaml:3"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("absolute path"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "nameless.yaml") << common << "hand_off: {command: [/bin/true]}\n";
  EXPECT_THROW(LoadDaemonConfig(dir / "nameless.yaml"), FileError);
  EXPECT_EQ(config.hand_off.timeout_s, 600);
  std::ofstream(dir / "timeout.yaml")
      << common << "hand_off: {command: [/bin/true, \"{name}\"], timeout_s: 5}\n";
  EXPECT_EQ(LoadDaemonConfig(dir / "timeout.yaml").hand_off.timeout_s, 5);
  std::ofstream(dir / "no_timeout.yaml")
      << common << "hand_off: {command: [/bin/true, \"{name}\"], timeout_s: 0}\n";
  EXPECT_THROW(LoadDaemonConfig(dir / "no_timeout.yaml"), FileError);
}

TEST_F(DaemonTest, MalformedRequestsGetA4xxWithAReasonAndWriteNothing) {
  Daemon daemon(config_);
  DaemonClient client = Client();
  auto expect = [&](const std::string& method, const std::string& path, const std::string& body,
                    int status, const std::string& reason_part) {
    const DaemonReply reply = client.Request(method, path, body);
    EXPECT_EQ(reply.status, status) << method << " " << path << " " << body;
    ASSERT_TRUE(reply.body.contains("error")) << reply.body.dump();
    EXPECT_NE(reply.body["error"].get<std::string>().find(reason_part), std::string::npos)
        << reply.body.dump();
  };
  expect("POST", "/v1/sessions", "{not json", 400, "request body: not valid JSON");
  // Issue 25, finding 5: nesting is bounded like every JSON reader's.
  expect("POST", "/v1/sessions", std::string(200000, '[') + std::string(200000, ']'), 400,
         "request body: arrays and objects nested more than 64 deep");
  expect("POST", "/v1/sessions", R"({"name": "x"})", 400, "expected");
  expect("POST", "/v1/sessions", R"({"name": 3, "plan": "p"})", 400, "expected");
  expect("POST", "/v1/sessions", json{{"name", "x"}, {"plan", "p"}, {"path", "/"}}.dump(), 400,
         "unknown field");
  for (const std::string name : {"../escape", "/tmp/abs", "..", ".hidden", "a/b"}) {
    expect("POST", "/v1/sessions", json{{"name", name}, {"plan", testing::SmallPlanYaml()}}.dump(),
           400, "invalid session name");
  }
  expect("POST", "/v1/sessions",
         json{{"name", "bad"}, {"plan", "sample: s\npositions:\n  - {camera_arm: abc}\n"}}.dump(),
         400, "plan of bad:3:");
  expect("POST", "/v1/sessions",
         json{{"name", "far"}, {"plan", "sample: s\npositions:\n  - {camera_arm: 95}\n"}}.dump(),
         400, "outside the axis limits");
  expect("POST", "/v1/sessions", std::string(HttpServer::kMaxBody + 10, 'x'), 413, "1 MiB");
  // Issue 15, finding 2: a 150-byte plan asked for 2e9 positions (9 s, 2.6 GB, then 500).
  expect("POST", "/v1/sessions",
         json{{"name", "huge"},
              {"plan",
               "sample: s\npositions: {symmetric_arms: {from_deg: 20, to_deg: 60, "
               "count: 2000000000}}\n"}}
             .dump(),
         400, "count must be between 1 and 1000");
  // Found by fuzz_daemon_request: the parser's message quotes the invalid UTF-8 byte, which
  // made the error answer itself throw (500 instead of 400).
  expect("POST", "/v1/sessions", "{\"name\": \"x\", \"plan\": \"count: \xb2\"}", 400,
         "not valid JSON");
  expect("GET", "/v1/nowhere", "", 404, "no such endpoint");
  expect("GET", "/v1/pause", "", 405, "POST");
  expect("POST", "/v1/pause", "", 409, "no session is running");
  expect("POST", "/v1/abort", "[1]", 400, "object");
  expect("POST", "/v1/sessions/ghost/resume", "", 404, "no session");
  expect("POST", "/v1/sessions/..%2F..%2Fx/resume", "", 400, "invalid session name");

  // Nothing was created anywhere: the data directory holds no session, its parent nothing new.
  EXPECT_TRUE(fs::is_empty(config_.data_dir));
  EXPECT_FALSE(fs::exists(rig_.dir / "escape"));
  EXPECT_FALSE(fs::exists("/tmp/abs"));

  client.Submit("taken", testing::SmallPlanYaml());
  expect("POST", "/v1/sessions", json{{"name", "taken"}, {"plan", testing::SmallPlanYaml()}}.dump(),
         409, "already exists");
  daemon.WaitIdle();
  expect("POST", "/v1/sessions/taken/resume", "", 409, "complete");
}

TEST_F(DaemonTest, ASecondClientAndAClientThatHangsUpDoNotDisturbTheRun) {
  Daemon daemon(config_);
  DaemonClient first = Client();
  first.Submit("shared", testing::SmallPlanYaml());
  // A client that connects, sends half a request and goes away.
  for (int i = 0; i < 3; ++i) {
    const int fd = ConnectUnixSocket(config_.socket);
    const std::string half = "POST /v1/sessions HTTP/1.1\r\nContent-Length: 100\r\n\r\n{\"na";
    ASSERT_GT(::send(fd, half.data(), half.size(), MSG_NOSIGNAL), 0);
    ::close(fd);
  }
  // A second client watches while the first one is gone.
  DaemonClient second = Client();
  const json watched = WaitForStatus([](const json& s) { return s.contains("progress"); });
  EXPECT_EQ(watched["session"], "shared");
  EXPECT_EQ(second.Sessions()["running"], "shared");
  daemon.WaitIdle();
  EXPECT_EQ(second.Status()["progress"]["frames_recorded"], 6);
  EXPECT_EQ(ReadSession(config_.data_dir / "shared").exit_status, "success");
}

TEST_F(DaemonTest, LoopbackTcpNeedsTheBearerToken) {
  // A free port, found by binding to port 0.
  const int probe = ListenLoopbackTcp(0);
  config_.tcp_port = BoundPort(probe);
  ::close(probe);
  config_.token = "0123456789abcdef-test-token";
  Daemon daemon(config_);
  EXPECT_EQ(DaemonClient(daemon.tcp_port(), "").Request("GET", "/v1/status").status, 401);
  EXPECT_EQ(DaemonClient(daemon.tcp_port(), "wrong-token-wrong-token")
                .Request("GET", "/v1/status")
                .status,
            401);
  EXPECT_EQ(DaemonClient(daemon.tcp_port(), config_.token).Status()["state"], "idle");
  // The Unix socket needs no token: its permission is the access control.
  EXPECT_EQ(Client().Status()["state"], "idle");
}

TEST_F(DaemonTest, RestartResumesTheRunningSessionAndTheQueueWhenConfigured) {
  {
    Daemon daemon(config_);
    Client().Submit("interrupted", LongPlan());
    Client().Submit("waiting", testing::SmallPlanYaml());
    WaitForStatus([](const json& s) {
      return s.contains("progress") && s["progress"]["frames_recorded"].get<int>() >= 2;
    });
    const json listed = Client().Sessions();
    ASSERT_EQ(listed["sessions"].size(), 2u);
    EXPECT_EQ(listed["sessions"][0]["exit_status"], "running");
    EXPECT_EQ(listed["sessions"][1]["exit_status"], "queued");
  }  // the daemon stops mid-session, with one session still queued
  EXPECT_FALSE(ReadSession(config_.data_dir / "interrupted").Complete());
  {
    Daemon daemon(config_);  // not configured to resume: lists both as resumable
    const json listed = Client().Sessions();
    ASSERT_EQ(listed["sessions"].size(), 2u);
    EXPECT_EQ(listed["sessions"][0]["resumable"], true);
    EXPECT_EQ(listed["sessions"][1]["resumable"], true);
    EXPECT_EQ(Client().Status()["state"], "idle");
  }
  config_.resume_interrupted = true;
  Daemon daemon(config_);
  daemon.WaitIdle();
  for (const auto& [name, frames] : {std::pair{"interrupted", 16u}, std::pair{"waiting", 6u}}) {
    const SessionContents s = ReadSession(config_.data_dir / name);
    EXPECT_EQ(s.exit_status, "success") << name;
    EXPECT_EQ(s.frames.size(), frames) << name;
    EXPECT_TRUE(VerifySession(config_.data_dir / name).ok()) << name;
  }
}

}  // namespace
}  // namespace brdfrig::acquire
