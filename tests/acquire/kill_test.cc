// The capture survives SIGKILL at any instant: a child process running the capture is killed
// at random instrumented points in every phase (moving, exposing, downloading, writing,
// recording) and at random times, resumed each time, and every finished session must hold
// every planned frame exactly once, with right hashes, no stray file, and bytes identical to
// an uninterrupted run (the simulated scene has no noise, so it is deterministic).
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <thread>

#include "common/sha256.h"
#include "session/session_reader.h"
#include "session/session_verify.h"
#include "tests/acquire/test_rig.h"

namespace brdfrig::acquire {

using session::ReadSession;
using session::VerifyReport;
using session::VerifySession;

namespace {

namespace fs = std::filesystem;

struct Child {
  int status = 0;
  bool killed() const { return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL; }
  bool succeeded() const { return WIFEXITED(status) && WEXITSTATUS(status) == 0; }
};

// Runs the helper; kill_at > 0 makes it kill itself at that instrumented point, kill_after_ms
// > 0 makes the parent kill it after that delay.
Child RunHelper(const testing::TestRig& rig, const fs::path& session, int kill_at,
                int kill_after_ms, const fs::path& kill_log) {
  const pid_t pid = fork();
  if (pid == 0) {
    if (kill_at > 0) {
      setenv("BRDFRIG_TEST_KILL_AT", std::to_string(kill_at).c_str(), 1);
      setenv("BRDFRIG_TEST_KILL_LOG", kill_log.c_str(), 1);
    }
    // Keep the test's output readable: the helper's summary lines go nowhere.
    freopen("/dev/null", "w", stdout);
    execl(CAPTURE_HELPER, CAPTURE_HELPER, rig.rig_file.c_str(), rig.plan_file.c_str(),
          session.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  if (kill_after_ms > 0) {
    std::this_thread::sleep_for(std::chrono::milliseconds(kill_after_ms));
    kill(pid, SIGKILL);
  }
  Child child;
  waitpid(pid, &child.status, 0);
  return child;
}

std::map<std::pair<int, int>, std::string> Hashes(const session::SessionContents& s) {
  std::map<std::pair<int, int>, std::string> hashes;
  for (const session::RecordedFrame& f : s.frames)
    hashes[{f.position_index, f.bracket_index}] = f.sha256;
  return hashes;
}

TEST(KillTest, SessionsKilledAtRandomMomentsResumeToTheUninterruptedResult) {
  const auto rig = testing::MakeTestRig("kill");
  const fs::path kill_log = rig.dir / "kill_log.txt";

  const Child reference_run = RunHelper(rig, rig.sessions / "reference", 0, 0, kill_log);
  ASSERT_TRUE(reference_run.succeeded()) << "status " << reference_run.status;
  const session::SessionContents reference = ReadSession(rig.sessions / "reference");
  ASSERT_EQ(reference.frames.size(), 6u);
  const auto reference_hashes = Hashes(reference);

  std::mt19937 rng(20261129);
  // A full run has 3 positions x (2 move points + 2 shots x 6 points) = 42 points: most runs
  // die, some after completing a position or two.
  std::uniform_int_distribution<int> point(1, 40);
  std::uniform_int_distribution<int> delay_ms(1, 60);
  int self_kills = 0, timed_kills = 0;
  std::vector<fs::path> sessions;
  for (int s = 0; self_kills < 50 || timed_kills < 10; ++s) {
    const fs::path session = rig.sessions / ("killed" + std::to_string(s));
    sessions.push_back(session);
    for (int attempt = 0;; ++attempt) {
      ASSERT_LT(attempt, 60) << "session " << s << " never finished";
      // The first tries of a session are killed by the parent at random times instead (any
      // code, including start-up and session creation).
      const bool timed = attempt < 2 && timed_kills < 10;
      const Child child = attempt >= 40 ? RunHelper(rig, session, 0, 0, kill_log)
                          : timed       ? RunHelper(rig, session, 0, delay_ms(rng), kill_log)
                                        : RunHelper(rig, session, point(rng), 0, kill_log);
      if (child.succeeded()) break;
      ASSERT_TRUE(child.killed()) << "session " << s << ": helper exited with status "
                                  << child.status;
      (timed ? timed_kills : self_kills)++;
    }
  }

  std::map<std::string, int> phases;
  {
    std::ifstream in(kill_log);
    for (std::string line; std::getline(in, line);) ++phases[line];
  }
  for (const char* phase : {"moving", "exposing", "downloading", "writing", "recording"}) {
    EXPECT_GT(phases[phase], 0) << "no kill while " << phase;
  }
  EXPECT_GE(self_kills + timed_kills, 50);

  for (const fs::path& dir : sessions) {
    SCOPED_TRACE(dir.string());
    const session::SessionContents s = ReadSession(dir);
    EXPECT_EQ(s.exit_status, "success");
    EXPECT_TRUE(s.Complete());
    ASSERT_EQ(s.frames.size(), 6u);  // exactly once: (position, bracket) is unique
    EXPECT_EQ(Hashes(s), reference_hashes);
    for (const session::RecordedFrame& f : s.frames) EXPECT_EQ(Sha256FileHex(f.file), f.sha256);
    const VerifyReport report = VerifySession(dir);
    EXPECT_TRUE(report.ok()) << report.ToString();
    for (const auto& entry : fs::recursive_directory_iterator(dir)) {
      EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
  }
  // A kill while a session was being created leaves .NAME.tmp-PID beside the sessions, not in
  // them: the next capture must have removed every one (issue 15, finding 4).
  for (const auto& entry : fs::directory_iterator(rig.sessions)) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
  std::printf("%d self-inflicted kills, %d timed kills over %zu sessions; phases:", self_kills,
              timed_kills, sessions.size());
  for (const auto& [phase, n] : phases) std::printf(" %s %d", phase.c_str(), n);
  std::printf("\n");
}

}  // namespace
}  // namespace brdfrig::acquire
