// `brdfrig batch collect` and `batch run` as a person runs them, against a job directory
// written by hand and stand-ins for sbatch and sacct placed first in PATH: an unreadable result
// is that item's failure, a capture name with a newline stays on its line, a SIGTERM while
// sbatch runs does not lose the submission (issue 25, finding 10), and a killed writer's
// temporary result is cleaned by the next one (finding 11), and `batch run` keeps such a name on
// its status line.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "batch/job_dir.h"
#include "batch/manifest.h"
#include "tests/common/run_brdfrig.h"

namespace brdfrig::batch {
namespace {

namespace fs = std::filesystem;

class JobCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    root_ = fs::temp_directory_path() / ("batch_job_cli_" + test);
    fs::remove_all(root_);
    fs::create_directories(root_ / "job" / "results");
    fs::create_directories(root_ / "bin");
    Manifest manifest;
    manifest.software = std::string("brdfrig ") + BRDFRIG_VERSION;
    manifest.output = root_ / "fits";
    for (const std::string name : {"a", "b", "bad\nname"}) {
      const fs::path capture = root_ / "archive" / name;
      manifest.items.push_back({static_cast<int>(manifest.items.size()), capture,
                                manifest.output / name / "material.json"});
    }
    WriteManifest(root_ / "job" / "manifest.json", manifest);
    std::ofstream(root_ / "job" / "array.sbatch") << "#!/bin/bash\n#SBATCH --array=0-2\n";
    // The stand-ins log their arguments; sacct answers what scheduler.txt holds.
    Script("sbatch", "echo \"$@\" >> '" + (root_ / "sbatch_calls").string() + "'\n" + "if [ -e '" +
                         (root_ / "term_caller").string() + "' ]; then kill -TERM $PPID; " +
                         "sleep 0.3; fi\necho 77\n");
    Script("sacct", "cat '" + (root_ / "scheduler.txt").string() + "' 2>/dev/null\n");
    Script("squeue", "exit 1\n");
    const char* path = std::getenv("PATH");
    old_path_ = path == nullptr ? "" : path;
    ::setenv("PATH", ((root_ / "bin").string() + ":" + old_path_).c_str(), 1);
  }

  void TearDown() override {
    ::setenv("PATH", old_path_.c_str(), 1);
    fs::remove_all(root_);
  }

  void Script(const std::string& name, const std::string& body) {
    const fs::path file = root_ / "bin" / name;
    std::ofstream(file) << "#!/bin/sh\n" << body;
    fs::permissions(file, fs::perms::owner_all);
  }

  std::vector<std::string> Lines(const fs::path& file) const {
    std::ifstream in(file);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  brdfrig::testing::CommandResult Collect(const std::string& options = "") const {
    return brdfrig::testing::RunBrdfrig("batch collect '" + (root_ / "job").string() + "'" +
                                        options);
  }

  fs::path root_;
  std::string old_path_;
};

// One malformed result aborted the whole report ("error: ... malformed task result"), a FIFO
// the same, and a capture name with a newline split its line in two.
TEST_F(JobCliTest, UnreadableResultsAreTheirItemsFailuresAndEveryItemKeepsItsLine) {
  std::ofstream(root_ / "job" / "results" / "0.json") << "{\"index\": 0, ";
  ASSERT_EQ(::mkfifo((root_ / "job" / "results" / "1.json").c_str(), 0600), 0);
  const auto result = Collect();
  EXPECT_EQ(result.status, 1) << result.output;
  const std::string output = result.output;
  EXPECT_NE(output.find(
                "FAILED  0 " + (root_ / "archive" / "a").string() +
                ": its result cannot be read: " + (root_ / "job" / "results" / "0.json").string()),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("FAILED  1 " + (root_ / "archive" / "b").string() +
                        ": its result cannot be read: " +
                        (root_ / "job" / "results" / "1.json").string() + ": not a regular file"),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("NO RESULT  2 $'" + (root_ / "archive").string() + "/bad\\nname': "),
            std::string::npos)
      << output;
  EXPECT_NE(output.find("3 item(s): 0 succeeded, 0 partial, 2 failed, 1 without a result"),
            std::string::npos)
      << output;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_FALSE(line.starts_with("name")) << "a capture's name split its line:\n" << output;
  }
  // The failures are what --resubmit submits again.
  const auto resubmitted = Collect(" --resubmit");
  EXPECT_EQ(resubmitted.status, 1) << resubmitted.output;
  EXPECT_EQ(Lines(root_ / "sbatch_calls"),
            (std::vector<std::string>{"--parsable --array=0-2 " +
                                      (root_ / "job" / "array.sbatch").string()}));
}

// SIGTERM while sbatch ran killed collect before it recorded the accepted job, so the next
// --resubmit submitted the same items a second time.
TEST_F(JobCliTest, SigtermWhileSbatchRunsStillRecordsTheSubmission) {
  std::ofstream(root_ / "term_caller") << "sbatch sends SIGTERM to its caller\n";
  const auto interrupted = Collect(" --resubmit");
  // Ended by the SIGTERM once the job is recorded (143 where popen's shell reports it).
  EXPECT_TRUE(interrupted.status == -1 || interrupted.status == 143) << interrupted.output;
  EXPECT_EQ(Lines(root_ / "job" / "submissions.txt"), (std::vector<std::string>{"77 0-2"}));

  fs::remove(root_ / "term_caller");
  std::ofstream(root_ / "scheduler.txt") << "77_[0-2]|PENDING|Priority\n";
  const auto again = Collect(" --resubmit");
  EXPECT_EQ(again.status, 1) << again.output;
  EXPECT_NE(again.output.find("active  0 "), std::string::npos) << again.output;
  EXPECT_EQ(Lines(root_ / "sbatch_calls").size(), 1u) << "the items were submitted twice";
}

// The pid of a process that has ended.
pid_t DeadPid() {
  const pid_t pid = ::fork();
  if (pid == 0) ::_exit(0);
  ::waitpid(pid, nullptr, 0);
  return pid;
}

// Issue 25, finding 11: the temporaries of writers killed between write and rename stayed
// beside their outputs forever.
TEST_F(JobCliTest, ATaskRemovesTheTemporariesKilledWritersLeftBesideItsResultAndNothingElse) {
  const fs::path results = root_ / "job" / "results";
  const std::string dead = std::to_string(DeadPid());
  const auto hour_ago = fs::file_time_type::clock::now() - std::chrono::hours(1);
  const fs::path stale_old_pattern = results / ("0.json.tmp-" + dead);
  const fs::path stale = results / ("0.json.tmp-" + dead + "-0badcafe");
  const fs::path other_output = results / ("1.json.tmp-" + dead + "-0badcafe");
  const fs::path link = results / ("0.json.tmp-" + dead + "-0000beef");
  const fs::path victim = root_ / "victim";
  std::ofstream(victim) << "precious";
  for (const fs::path& file : {stale_old_pattern, stale, other_output}) {
    std::ofstream(file) << "torn";
    fs::last_write_time(file, hour_ago);
  }
  fs::create_symlink(victim, link);
  const auto result =
      brdfrig::testing::RunBrdfrig("batch run '" + (root_ / "job").string() + "' --index 0");
  EXPECT_EQ(result.status, 1) << result.output;  // its capture does not exist
  EXPECT_TRUE(fs::exists(results / "0.json")) << result.output;
  EXPECT_FALSE(fs::exists(stale_old_pattern));
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(other_output)) << "another output's temporary is not this write's";
  EXPECT_TRUE(fs::is_symlink(link)) << "a symlink is not a temporary this code made";
  std::ifstream in(victim);
  std::string text;
  std::getline(in, text);
  EXPECT_EQ(text, "precious");
}

// `batch run` printed the item's capture and material as they are: a name with a newline split
// the task's one status line (the Slurm log a lab greps) in two.
TEST_F(JobCliTest, ATaskWithANewlineInItsCaptureNameKeepsItsStatusOnOneLine) {
  const auto result =
      brdfrig::testing::RunBrdfrig("batch run '" + (root_ / "job").string() + "' --index 2");
  EXPECT_EQ(result.status, 1) << result.output;  // the capture does not exist: that item fails
  const std::string quoted = "$'" + (root_ / "archive").string() + "/bad\\nname'";
  EXPECT_NE(result.output.find(" 2 " + quoted + " -> $'"), std::string::npos) << result.output;
  std::istringstream lines(result.output);
  for (std::string line; std::getline(lines, line);) {
    EXPECT_FALSE(line.starts_with("name")) << "a capture's name split its line:\n" << result.output;
  }
}

}  // namespace
}  // namespace brdfrig::batch
