// The daemon's hand-off command on its own: placeholders, a command that leaves a child holding
// its output, one past its timeout, one running when the daemon stops, and what the log says.
// Issue 25, finding 10.
#include "acquire/hand_off.h"

#include <signal.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>
#include <thread>

#include "common/error.h"

namespace brdfrig::acquire {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

fs::path FreshDir(const std::string& name) {
  const fs::path dir =
      fs::temp_directory_path() / ("brdfrig_hand_off_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Running: the process exists and is not a zombie waiting for its parent.
bool Running(const std::string& pid_text) {
  std::ifstream stat("/proc/" + pid_text + "/stat");
  std::string line;
  if (!std::getline(stat, line)) return false;
  const std::size_t close = line.rfind(')');
  return close != std::string::npos && close + 2 < line.size() && line[close + 2] != 'Z';
}

std::string FirstLine(const fs::path& file) {
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  return line;
}

// "{name}" inside the expanded "{session}" (a data_dir named so) was replaced a second time.
TEST(HandOffTest, PlaceholdersAreReplacedOnceInTheCommandAsWritten) {
  HandOff hand_off;
  hand_off.command = {"/bin/x", "{session}", "/jobs/{name}", "{name}:{session}", "{nam{name}e}"};
  EXPECT_EQ(HandOffCommand(hand_off, "/srv/{name}/data/s1", "s1"),
            (std::vector<std::string>{"/bin/x", "/srv/{name}/data/s1", "/jobs/s1",
                                      "s1:/srv/{name}/data/s1", "{nams1e}"}));
}

TEST(HandOffTest, TimeoutMustBePositive) {
  HandOff hand_off;
  hand_off.command = {"/bin/true", "{name}"};
  hand_off.timeout_s = 0;
  EXPECT_THROW(hand_off.Validate(), OptionsError);
  hand_off.timeout_s = 1;
  EXPECT_NO_THROW(hand_off.Validate());
}

// A command that exits while a background child still holds its stdout kept the daemon
// waiting for the child (`sleep infinity &`: forever).
TEST(HandOffTest, ACommandThatLeavesAChildHoldingItsOutputIsDoneWhenItExitsAndTheChildIsEnded) {
  const fs::path dir = FreshDir("leftover");
  HandOff hand_off;
  hand_off.command = {"/bin/sh",
                      "-c",
                      "sleep 20 & echo $! > \"$1\"; echo started",
                      "sh",
                      (dir / "child.pid").string(),
                      "{name}"};
  const auto start = Clock::now();
  const std::string line = RunHandOff(hand_off, dir, "s1");
  EXPECT_LT(SecondsSince(start), 1.5 * kHandOffGraceS + 1) << line;
  EXPECT_NE(line.find("session s1 handed off: /bin/sh -c"), std::string::npos) << line;
  EXPECT_NE(line.find(" exited 0; ended 1 process(es) it left running"), std::string::npos) << line;
  const std::string child = FirstLine(dir / "child.pid");
  ASSERT_FALSE(child.empty());
  EXPECT_FALSE(Running(child)) << "the background child " << child << " outlived the hand-off";
  fs::remove_all(dir);
}

TEST(HandOffTest, ACommandPastItsTimeoutIsEndedWithItsChildrenEvenWhenTheDaemonBlocksSigterm) {
  const fs::path dir = FreshDir("timeout");
  HandOff hand_off;
  hand_off.command = {
      "/bin/sh", "-c", "sleep 20 & echo $! > \"$1\"; sleep 20", "sh", (dir / "child.pid").string(),
      "{name}"};
  hand_off.timeout_s = 0.3;
  // The daemon blocks SIGTERM in every thread (it takes it with sigwait); a command spawned
  // with that mask would ignore the SIGTERM that ends it.
  sigset_t term, old;
  sigemptyset(&term);
  sigaddset(&term, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &term, &old);
  const auto start = Clock::now();
  const std::string line = RunHandOff(hand_off, dir, "s2");
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  EXPECT_LT(SecondsSince(start), 0.3 + kHandOffGraceS) << line;
  EXPECT_NE(line.find("session s2 hand-off timed out after 0.3 s, so it was ended: /bin/sh"),
            std::string::npos)
      << line;
  EXPECT_NE(line.find("(exit status 143); run it again by hand"), std::string::npos) << line;
  const std::string child = FirstLine(dir / "child.pid");
  ASSERT_FALSE(child.empty());
  EXPECT_FALSE(Running(child)) << "the background child " << child << " outlived the hand-off";
  fs::remove_all(dir);
}

TEST(HandOffTest, ARunningCommandIsEndedWhenTheDaemonStops) {
  const fs::path dir = FreshDir("stop");
  HandOff hand_off;
  hand_off.command = {"/bin/sh", "-c", "sleep 20", "sh", "{name}"};
  std::atomic<bool> stop{false};
  std::thread stopper([&stop] {
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    stop = true;
  });
  const auto start = Clock::now();
  const std::string line = RunHandOff(hand_off, dir, "s3", &stop);
  stopper.join();
  EXPECT_LT(SecondsSince(start), 0.2 + kHandOffGraceS) << line;
  EXPECT_NE(line.find("session s3 hand-off was ended because the daemon is stopping"),
            std::string::npos)
      << line;
  fs::remove_all(dir);
}

TEST(HandOffTest, AFailureIsLoggedWithItsLastStderrLineAndAMissingProgramWithWhy) {
  const fs::path dir = FreshDir("failure");
  HandOff hand_off;
  hand_off.command = {"/bin/sh", "-c", "echo out; echo one >&2; echo two >&2; exit 3", "{name}"};
  const std::string line = RunHandOff(hand_off, dir, "s4");
  EXPECT_NE(line.find(" exited 3: two"), std::string::npos) << line;
  EXPECT_EQ(line.find("ended"), std::string::npos) << line;
  hand_off.command = {(dir / "missing").string(), "{name}"};
  const std::string missing = RunHandOff(hand_off, dir, "s4");
  EXPECT_NE(missing.find(" exited 127: " + (dir / "missing").string() + ": No such file"),
            std::string::npos)
      << missing;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace brdfrig::acquire
