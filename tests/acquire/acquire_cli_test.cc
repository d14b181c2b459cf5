// The acquisition commands as a person runs them: the real `brdfrig` executable, its exit
// statuses and the lines it prints — plan check, capture (and Ctrl-C during a capture),
// session verify, and the daemon with its client commands.
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <thread>

#include "session/session_reader.h"
#include "session/sqlite_db.h"
#include "tests/acquire/test_rig.h"
#include "tests/common/run_brdfrig.h"

// GCC says __SANITIZE_ADDRESS__, clang (the asan preset's compiler) __has_feature.
#if defined(__SANITIZE_ADDRESS__)
#define BRDFRIG_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BRDFRIG_UNDER_ASAN 1
#endif
#endif
#ifndef BRDFRIG_UNDER_ASAN
#define BRDFRIG_UNDER_ASAN 0
#endif
namespace brdfrig::acquire {

using session::ReadSession;
using session::SessionContents;

namespace {

namespace fs = std::filesystem;

using Result = brdfrig::testing::CommandResult;

Result Brdfrig(const std::string& arguments) { return brdfrig::testing::RunBrdfrig(arguments); }

pid_t Spawn(const std::vector<std::string>& arguments, const fs::path& log) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    std::vector<std::string> args = arguments;
    args.insert(args.begin(), BRDFRIG_BINARY);
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    freopen(log.c_str(), "w", stderr);
    freopen("/dev/null", "w", stdout);
    execv(BRDFRIG_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

int Wait(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string Q(const fs::path& p) { return "'" + p.string() + "'"; }

TEST(AcquireCliTest, PlanCheckCaptureAndVerifyReportThroughExitStatus) {
  const auto rig = testing::MakeTestRig("cli_capture");
  const Result ok = Brdfrig("plan check --rig " + Q(rig.rig_file) + " --plan " + Q(rig.plan_file));
  EXPECT_EQ(ok.status, 0) << ok.output;
  EXPECT_NE(ok.output.find("plan OK"), std::string::npos) << ok.output;

  std::ofstream(rig.dir / "bad.yaml") << "sample: s\npositions:\n  - {camera_arm: 20}\n"
                                         "  - {camera_arm: 95}\n";
  const Result bad =
      Brdfrig("plan check --rig " + Q(rig.rig_file) + " --plan " + Q(rig.dir / "bad.yaml"));
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("bad.yaml:4:"), std::string::npos) << bad.output;

  const std::string capture = "capture --rig " + Q(rig.rig_file) + " --plan " + Q(rig.plan_file) +
                              " -o " + Q(rig.sessions / "s");
  const Result captured = Brdfrig(capture);
  EXPECT_EQ(captured.status, 0) << captured.output;
  EXPECT_NE(captured.output.find("success"), std::string::npos) << captured.output;
  EXPECT_EQ(Brdfrig(capture).status, 1);  // never over an existing session

  const Result verified = Brdfrig("session verify " + Q(rig.sessions / "s"));
  EXPECT_EQ(verified.status, 0) << verified.output;
  std::ofstream(rig.sessions / "s" / "frames" / "p002_b1.png", std::ios::app) << "tampered";
  const Result tampered = Brdfrig("session verify " + Q(rig.sessions / "s"));
  EXPECT_EQ(tampered.status, 1) << tampered.output;
  EXPECT_NE(tampered.output.find("changed: frames/p002_b1.png"), std::string::npos)
      << tampered.output;
}

TEST(AcquireCliTest, CtrlCAbortsACaptureCleanlyAndResumeFinishesIt) {
  const auto rig = testing::MakeTestRig("cli_ctrl_c");
  std::string scene = testing::SmallSceneYaml();
  scene.replace(scene.find("reopen_s: 2"), 11, "reopen_s: 2\n  real_time_factor: 0.1");
  std::ofstream(rig.dir / "scene.yaml") << scene;
  const fs::path session = rig.sessions / "s";
  const pid_t pid = Spawn({"capture", "--rig", rig.rig_file.string(), "--plan",
                           rig.plan_file.string(), "-o", session.string()},
                          rig.dir / "capture.log");
  // Ctrl-C once the first frame is recorded (the run has more than a second to go then).
  for (int i = 0; i < 1000 && !fs::exists(session / "frames" / "p000_b0.png"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGINT);
  EXPECT_EQ(Wait(pid), 1);
  const SessionContents aborted = ReadSession(session);
  EXPECT_EQ(aborted.exit_status, "aborted");
  EXPECT_EQ(aborted.stop_reason, "interrupted (Ctrl-C)");
  EXPECT_FALSE(aborted.Complete());

  const Result resumed =
      Brdfrig("capture --rig " + Q(rig.rig_file) + " -o " + Q(session) + " --resume");
  EXPECT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_TRUE(ReadSession(session).Complete());
}

TEST(AcquireCliTest, DaemonAndItsClientCommands) {
  const auto rig = testing::MakeTestRig("cli_daemon");
  char socket_dir[] = "/tmp/brdfrig-cli-XXXXXX";  // sun_path holds 107 bytes
  ASSERT_NE(mkdtemp(socket_dir), nullptr);
  const fs::path socket = fs::path(socket_dir) / "d.sock";
  std::ofstream(rig.dir / "daemon.yaml")
      << "data_dir: data\nrig: rig.yaml\nsocket: " << socket.string() << "\n";
  const pid_t daemon =
      Spawn({"daemon", "--config", (rig.dir / "daemon.yaml").string()}, rig.dir / "daemon.log");
  for (int i = 0; i < 200 && !fs::exists(socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const std::string at = " --socket " + Q(socket);

  const Result submitted = Brdfrig("submit" + at + " --name d1 --follow " + Q(rig.plan_file));
  EXPECT_EQ(submitted.status, 0) << submitted.output;
  EXPECT_NE(submitted.output.find("session d1: success"), std::string::npos) << submitted.output;
  const Result status = Brdfrig("status" + at);
  EXPECT_EQ(status.status, 0) << status.output;
  EXPECT_NE(status.output.find("daemon idle"), std::string::npos) << status.output;
  EXPECT_NE(status.output.find("d1"), std::string::npos) << status.output;
  const Result pause = Brdfrig("pause" + at);
  EXPECT_EQ(pause.status, 1);
  EXPECT_NE(pause.output.find("no session is running"), std::string::npos) << pause.output;
  const Result traversal = Brdfrig("submit" + at + " --name ../x " + Q(rig.plan_file));
  EXPECT_EQ(traversal.status, 1);
  EXPECT_NE(traversal.output.find("invalid session name"), std::string::npos) << traversal.output;
  // A plan that is not UTF-8 cannot travel as a JSON string: refused at its line and column,
  // before a request (it used to end in an internal json error).
  const fs::path latin1 = rig.dir / "latin1_plan.yaml";
  std::ofstream(latin1) << "sample: s\n# caf\xe9\npositions: []\n";
  const Result not_utf8 = Brdfrig("submit" + at + " --name d2 " + Q(latin1));
  EXPECT_EQ(not_utf8.status, 1);
  EXPECT_NE(not_utf8.output.find(latin1.string() + ":2:6: not UTF-8 text (byte 0xe9"),
            std::string::npos)
      << not_utf8.output;
  EXPECT_FALSE(fs::exists(rig.dir / "data" / "d2"));

  kill(daemon, SIGTERM);
  EXPECT_EQ(Wait(daemon), 0);
  EXPECT_FALSE(fs::exists(socket));
  EXPECT_EQ(ReadSession(rig.dir / "data" / "d1").exit_status, "success");
  fs::remove_all(socket_dir);
}

std::string FileText(const fs::path& file) {
  std::ifstream in(file);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Exit status of `pid` if it ends within `seconds`; else kills it and returns -2.
int WaitAtMost(pid_t pid, double seconds) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (std::chrono::steady_clock::now() < end) {
    if (waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  waitpid(pid, &status, 0);
  return -2;
}

// Issue 25, finding 10: `{name}` was replaced again inside the expanded `{session}` (a data_dir
// containing "{name}" gave the hand-off a directory that does not exist), and a hand-off that
// exited leaving a child on its stdout kept the daemon waiting: its outcome was never logged
// and SIGTERM waited for the child (`sleep infinity &`: forever).
TEST(AcquireCliTest, DaemonHandOffGetsItsSessionAndNeitherWaitsForNorLeavesItsChildren) {
  const auto rig = testing::MakeTestRig("cli_hand_off");
  char socket_dir[] = "/tmp/brdfrig-hand-XXXXXX";  // sun_path holds 107 bytes
  ASSERT_NE(mkdtemp(socket_dir), nullptr);
  const fs::path socket = fs::path(socket_dir) / "d.sock";
  const fs::path child_pid = rig.dir / "child.pid";
  std::ofstream(rig.dir / "daemon.yaml")
      << "data_dir: \"data-{name}\"\nrig: rig.yaml\nsocket: " << socket.string() << "\n"
      << "hand_off:\n  command: [/bin/sh, -c, 'sleep 30 & echo $! > \"$2\"; test -d \"$1\"', sh, "
         "\"{session}\", "
      << child_pid.string() << "]\n  timeout_s: 20\n";
  const fs::path log = rig.dir / "daemon.log";
  const pid_t daemon = Spawn({"daemon", "--config", (rig.dir / "daemon.yaml").string()}, log);
  for (int i = 0; i < 500 && !fs::exists(socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const Result submitted =
      Brdfrig("submit --socket " + Q(socket) + " --name d1 --follow " + Q(rig.plan_file));
  EXPECT_EQ(submitted.status, 0) << submitted.output;
  for (int i = 0; i < 500 && FileText(log).find("handed off") == std::string::npos; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const std::string logged = FileText(log);
  EXPECT_NE(logged.find("session d1 handed off: /bin/sh -c"), std::string::npos) << logged;
  // test -d "$1" exits 0: the session directory it got exists.
  EXPECT_NE(logged.find((rig.dir / "data-{name}" / "d1").string()), std::string::npos) << logged;
  EXPECT_NE(logged.find(" exited 0; ended 1 process(es)"), std::string::npos) << logged;
  const auto stop = std::chrono::steady_clock::now();
  kill(daemon, SIGTERM);
  EXPECT_EQ(WaitAtMost(daemon, 10), 0) << FileText(log);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - stop).count(), 5);
  const std::string child = FileText(child_pid);
  ASSERT_FALSE(child.empty());
  const int pid = std::stoi(child);
  const std::string stat = FileText("/proc/" + std::to_string(pid) + "/stat");
  const bool running = !stat.empty() && stat.find(") Z") == std::string::npos;
  EXPECT_FALSE(running) << "the hand-off's child " << pid << " outlived it: " << stat;
  if (running) kill(pid, SIGKILL);
  fs::remove_all(socket_dir);
}

// Issue 15, finding 1: two daemons with different sockets, or a daemon and a foreground
// capture, drove the same rig at once. Whoever comes second must fail at once, name the
// holder, and neither open a device nor create anything.
TEST(AcquireCliTest, OneOwnerOfTheRig) {
  const auto rig = testing::MakeTestRig("cli_owner");
  char socket_dir[] = "/tmp/brdfrig-owner-XXXXXX";
  ASSERT_NE(mkdtemp(socket_dir), nullptr);
  auto config = [&](const std::string& name, const std::string& data) {
    const fs::path file = rig.dir / (name + ".yaml");
    std::ofstream(file) << "data_dir: " << data << "\nrig: rig.yaml\nsocket: " << socket_dir << "/"
                        << name << ".sock\n";
    return file.string();
  };
  const pid_t daemon = Spawn({"daemon", "--config", config("d1", "data")}, rig.dir / "d1.log");
  const fs::path socket = fs::path(socket_dir) / "d1.sock";
  for (int i = 0; i < 500 && !fs::exists(socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(fs::exists(socket));
  const std::string holder = "pid " + std::to_string(daemon) + " (";

  const Result capture = Brdfrig("capture --rig " + Q(rig.rig_file) + " --plan " +
                                 Q(rig.plan_file) + " -o " + Q(rig.sessions / "s"));
  EXPECT_EQ(capture.status, 1) << capture.output;
  EXPECT_NE(capture.output.find("is in use by " + holder), std::string::npos) << capture.output;
  EXPECT_NE(capture.output.find("daemon --config"), std::string::npos) << capture.output;
  EXPECT_FALSE(fs::exists(rig.sessions / "s"));
  EXPECT_TRUE(fs::is_empty(rig.sessions)) << "nothing created, not even a temporary session";

  // Same data directory, another socket: refused on the data directory.
  const Result same_data = Brdfrig("daemon --config " + config("d2", "data"));
  EXPECT_EQ(same_data.status, 1) << same_data.output;
  EXPECT_NE(same_data.output.find("data directory"), std::string::npos) << same_data.output;
  EXPECT_NE(same_data.output.find(holder), std::string::npos) << same_data.output;
  EXPECT_FALSE(fs::exists(fs::path(socket_dir) / "d2.sock"));

  // Another data directory, same rig: refused on the rig's devices.
  const Result same_rig = Brdfrig("daemon --config " + config("d3", "data3"));
  EXPECT_EQ(same_rig.status, 1) << same_rig.output;
  EXPECT_NE(same_rig.output.find("the rig's"), std::string::npos) << same_rig.output;
  EXPECT_NE(same_rig.output.find(holder), std::string::npos) << same_rig.output;
  EXPECT_FALSE(fs::exists(fs::path(socket_dir) / "d3.sock"));

  const Result check = Brdfrig("rig check --rig " + Q(rig.rig_file));
  EXPECT_EQ(check.status, 1) << check.output;
  EXPECT_NE(check.output.find(holder), std::string::npos) << check.output;

  kill(daemon, SIGTERM);
  EXPECT_EQ(Wait(daemon), 0);
  // Released with its owner: the rig is free again.
  const Result after = Brdfrig("capture --rig " + Q(rig.rig_file) + " --plan " + Q(rig.plan_file) +
                               " -o " + Q(rig.sessions / "s"));
  EXPECT_EQ(after.status, 0) << after.output;
  fs::remove_all(socket_dir);
}

// Issue 15, finding 4: a frames.file cell holding "../" made `capture --resume` delete a file
// outside the session; a catalog from a newer brdfrig was misread; `--resume` of a missing
// session said "error: : cannot open file"; a killed creation's .NAME.tmp-PID stayed forever.
TEST(AcquireCliTest, ResumeTrustsNothingInTheCatalog) {
  const auto rig = testing::MakeTestRig("cli_resume_trust");
  const fs::path session = rig.sessions / "s";
  const std::string capture = "capture --rig " + Q(rig.rig_file) + " -o " + Q(session);
  ASSERT_EQ(Brdfrig(capture + " --plan " + Q(rig.plan_file)).status, 0);
  const fs::path victim = rig.dir / "victim.txt";
  std::ofstream(victim) << "not the session's";
  {
    // Position 2 made incomplete (a resume redoes it, deleting its frames), one of its frames
    // pointing outside the session.
    session::SqliteDb db(session / "session.sqlite", session::SqliteDb::Mode::kReadWrite);
    db.Exec("DELETE FROM positions WHERE position_index = 2");
    db.Exec(
        "UPDATE frames SET file = '../../victim.txt' WHERE position_index = 2 AND "
        "bracket_index = 0");
  }
  const Result escaped = Brdfrig(capture + " --resume");
  EXPECT_EQ(escaped.status, 1) << escaped.output;
  EXPECT_NE(escaped.output.find("frames.file '../../victim.txt'"), std::string::npos)
      << escaped.output;
  EXPECT_TRUE(fs::exists(victim));
  EXPECT_TRUE(fs::exists(session / "frames" / "p002_b1.png")) << "nothing deleted";
  const Result read = Brdfrig("reconstruct " + Q(session) + " -o " + Q(rig.dir / "m.json"));
  EXPECT_EQ(read.status, 1) << read.output;
  EXPECT_NE(read.output.find("must stay inside"), std::string::npos) << read.output;

  {
    session::SqliteDb db(session / "session.sqlite", session::SqliteDb::Mode::kReadWrite);
    db.Exec("UPDATE frames SET file = 'frames/p002_b0.png' WHERE file = '../../victim.txt'");
    db.Exec("UPDATE meta SET value = '99' WHERE key = 'schema_version'");
  }
  const Result newer = Brdfrig(capture + " --resume");
  EXPECT_EQ(newer.status, 1) << newer.output;
  EXPECT_NE(newer.output.find("schema_version 99, newer than this brdfrig"), std::string::npos)
      << newer.output;
  EXPECT_TRUE(fs::exists(session / "frames" / "p002_b1.png")) << "nothing deleted";
  const Result verify = Brdfrig("session verify " + Q(session));
  EXPECT_EQ(verify.status, 1) << verify.output;
  EXPECT_NE(verify.output.find("schema_version 99"), std::string::npos) << verify.output;

  const Result missing =
      Brdfrig("capture --rig " + Q(rig.rig_file) + " -o " + Q(rig.sessions / "nope") + " --resume");
  EXPECT_EQ(missing.status, 1) << missing.output;
  EXPECT_NE(missing.output.find("no session at '" + (rig.sessions / "nope").string() + "'"),
            std::string::npos)
      << missing.output;

  // A creation killed half-way (its pid is gone) is cleaned by the next capture beside it.
  const pid_t gone = fork();
  if (gone == 0) _exit(0);
  Wait(gone);
  const fs::path leftover = rig.sessions / (".t.tmp-" + std::to_string(gone));
  fs::create_directories(leftover / "frames");
  const Result next = Brdfrig(capture.substr(0, capture.find(" -o ")) + " --plan " +
                              Q(rig.plan_file) + " -o " + Q(rig.sessions / "t2"));
  EXPECT_EQ(next.status, 0) << next.output;
  EXPECT_FALSE(fs::exists(leftover));
  EXPECT_NE(next.output.find("removed " + leftover.string()), std::string::npos) << next.output;
}

// Issue 15, finding 2: `plan check` on /dev/zero ate memory and on a FIFO hung forever; every
// count from a plan needs a bound with a clear error.
TEST(AcquireCliTest, InputFilesAndCountsAreBounded) {
  const auto rig = testing::MakeTestRig("cli_bounds");
  // Under a memory cap and a time limit, so that the old behaviour fails the test instead of
  // exhausting the machine or hanging it.
  const std::string check = "plan check --rig " + Q(rig.rig_file) + " --plan ";
  auto run = [](const std::string& arguments) {
    Result result;
    // A 4 GB address-space cap catches a reader that eats memory; AddressSanitizer reserves
    // terabytes of shadow address space, so under it only the timeout bounds the run.
#if BRDFRIG_UNDER_ASAN
    const std::string cap = "";
#else
    const std::string cap = "ulimit -v 4000000; ";
#endif
    const std::string command =
        cap + "timeout 20 " + std::string(BRDFRIG_BINARY) + " " + arguments + " 2>&1";
    FILE* pipe = popen(command.c_str(), "r");
    std::array<char, 512> buffer;
    while (fgets(buffer.data(), buffer.size(), pipe) != nullptr) result.output += buffer.data();
    const int status = pclose(pipe);
    result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return result;
  };
  const auto start = std::chrono::steady_clock::now();
  const Result zero = run(check + "/dev/zero");
  EXPECT_EQ(zero.status, 1) << zero.output;
  EXPECT_NE(zero.output.find("/dev/zero: not a regular file"), std::string::npos) << zero.output;
  const fs::path fifo = rig.dir / "plan.fifo";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Result pipe = run(check + Q(fifo));
  EXPECT_EQ(pipe.status, 1) << pipe.output;  // 124 when it hangs until the timeout
  EXPECT_NE(pipe.output.find("not a regular file"), std::string::npos) << pipe.output;
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));

  std::ofstream(rig.dir / "many.yaml")
      << "sample: s\npositions: {symmetric_arms: {from_deg: 20, to_deg: 60, count: 2000000000}}\n";
  const Result many = run(check + Q(rig.dir / "many.yaml"));
  EXPECT_EQ(many.status, 1) << many.output;
  EXPECT_NE(many.output.find("many.yaml:2:"), std::string::npos) << many.output;
  EXPECT_NE(many.output.find("count must be between 1 and 1000"), std::string::npos) << many.output;
  std::string listed = "sample: s\npositions:\n";
  for (int i = 0; i < 1001; ++i) listed += "  - {camera_arm: 20, light_arm: -20}\n";
  std::ofstream(rig.dir / "listed.yaml") << listed;
  const Result list = run(check + Q(rig.dir / "listed.yaml"));
  EXPECT_EQ(list.status, 1) << list.output;
  EXPECT_NE(list.output.find("1001 positions: at most 1000"), std::string::npos) << list.output;
  std::ofstream(rig.dir / "bracket.yaml")
      << "sample: s\npositions:\n  - {camera_arm: 20, light_arm: -20}\nexposures: [1, 2, 3, 4, "
         "5, 6, 7, 8, 9, 10]\n";
  const Result bracket = run(check + Q(rig.dir / "bracket.yaml"));
  EXPECT_EQ(bracket.status, 1) << bracket.output;
  EXPECT_NE(bracket.output.find("10 exposures: a bracket has at most 9"), std::string::npos)
      << bracket.output;
}

// Issue 15, finding 3: 64 idle connections made every request, an emergency abort included,
// wait 30 s; a client that sends half a request must not hold up the others either.
TEST(AcquireCliTest, IdleAndSlowClientsCannotLockOutTheControlApi) {
  const auto rig = testing::MakeTestRig("cli_lockout");
  char socket_dir[] = "/tmp/brdfrig-lockout-XXXXXX";
  ASSERT_NE(mkdtemp(socket_dir), nullptr);
  const fs::path socket = fs::path(socket_dir) / "d.sock";
  std::ofstream(rig.dir / "daemon.yaml")
      << "data_dir: data\nrig: rig.yaml\nsocket: " << socket.string() << "\n";
  const pid_t daemon =
      Spawn({"daemon", "--config", (rig.dir / "daemon.yaml").string()}, rig.dir / "daemon.log");
  for (int i = 0; i < 500 && !fs::exists(socket); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(fs::exists(socket));
  std::vector<int> idle;
  for (int i = 0; i < 64; ++i) {
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::strncpy(address.sun_path, socket.c_str(), sizeof(address.sun_path) - 1);
    ASSERT_EQ(::connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    // A few send half a request and stall (slow clients); the rest say nothing at all.
    if (i % 8 == 0) {
      const std::string half =
          "POST /v1/sessions HTTP/1.1\r\nHost: x\r\nContent-Length: 100\r\n\r\n{";
      ASSERT_EQ(::send(fd, half.data(), half.size(), MSG_NOSIGNAL),
                static_cast<ssize_t>(half.size()));
    }
    idle.push_back(fd);
  }
  const std::string at = " --socket " + Q(socket);
  auto timed = [&](const std::string& arguments) {
    const auto start = std::chrono::steady_clock::now();
    const Result result = Brdfrig(arguments);
    return std::make_pair(result, std::chrono::steady_clock::now() - start);
  };
  const auto [status, status_time] = timed("status" + at);
  EXPECT_EQ(status.status, 0) << status.output;
  EXPECT_NE(status.output.find("daemon idle"), std::string::npos) << status.output;
  EXPECT_LT(status_time, std::chrono::seconds(2));
  const auto [abort, abort_time] = timed("abort" + at);
  EXPECT_NE(abort.output.find("no session is running"), std::string::npos) << abort.output;
  EXPECT_LT(abort_time, std::chrono::seconds(2));
  // Idle connections are closed by the daemon after a few seconds, not kept forever.
  char byte = 0;
  const auto waited = std::chrono::steady_clock::now();
  EXPECT_EQ(::recv(idle[1], &byte, 1, 0), 0) << "the daemon closes an idle connection";
  EXPECT_LT(std::chrono::steady_clock::now() - waited, std::chrono::seconds(10));
  for (const int fd : idle) ::close(fd);
  kill(daemon, SIGTERM);
  EXPECT_EQ(Wait(daemon), 0);
  fs::remove_all(socket_dir);
}

// Issue 15, finding 6: SIGHUP (the SSH session closed) killed a capture without a stop record
// and without stopping the axes; it is handled like Ctrl-C.
TEST(AcquireCliTest, HangUpAbortsACaptureCleanly) {
  const auto rig = testing::MakeTestRig("cli_sighup");
  std::string scene = testing::SmallSceneYaml();
  scene.replace(scene.find("reopen_s: 2"), 11, "reopen_s: 2\n  real_time_factor: 0.1");
  std::ofstream(rig.dir / "scene.yaml") << scene;
  const fs::path session = rig.sessions / "s";
  const pid_t pid = Spawn({"capture", "--rig", rig.rig_file.string(), "--plan",
                           rig.plan_file.string(), "-o", session.string()},
                          rig.dir / "capture.log");
  for (int i = 0; i < 1000 && !fs::exists(session / "frames" / "p000_b0.png"); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  kill(pid, SIGHUP);
  EXPECT_EQ(Wait(pid), 1) << "an exit, not death by the signal";
  const SessionContents aborted = ReadSession(session);
  EXPECT_EQ(aborted.exit_status, "aborted");
  EXPECT_EQ(aborted.stop_reason, "hung up (SIGHUP: the terminal closed)");
}

// Issue 15, finding 6: a TCP token file others can read was accepted silently.
TEST(AcquireCliTest, TokenFileReadableByOthersIsRefused) {
  const auto rig = testing::MakeTestRig("cli_token");
  std::ofstream(rig.dir / "token") << "0123456789abcdef-token\n";
  fs::permissions(rig.dir / "token", fs::perms::owner_read | fs::perms::owner_write |
                                         fs::perms::group_read | fs::perms::others_read);
  std::ofstream(rig.dir / "daemon.yaml")
      << "data_dir: data\nrig: rig.yaml\ntcp: {port: 1, token_file: token}\n";
  const Result refused = Brdfrig("daemon --config " + Q(rig.dir / "daemon.yaml"));
  EXPECT_EQ(refused.status, 1) << refused.output;
  EXPECT_NE(refused.output.find("daemon.yaml:3:"), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("mode 0644: others may read it"), std::string::npos)
      << refused.output;
  EXPECT_FALSE(fs::exists(rig.dir / "data")) << "refused before anything was created";
}

}  // namespace
}  // namespace brdfrig::acquire
