// What goes to Slurm and what comes back, without a cluster: array index lists, the sbatch
// script, squeue/sacct lines, the task index from the environment.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

#include "batch/array_spec.h"
#include "batch/sbatch_script.h"
#include "batch/slurm.h"
#include "batch/task.h"
#include "common/error.h"
#include "tests/common/run_brdfrig.h"

namespace brdfrig::batch {
namespace {

namespace fs = std::filesystem;

TEST(ArraySpecTest, RangesCompressAndExpandBackWithTheThrottleAndBracketsIgnored) {
  EXPECT_EQ(ArraySpec({7, 0, 1, 2, 3, 2}), "0-3,7");
  EXPECT_EQ(ArraySpec({4}, 2), "4%2");
  EXPECT_EQ(ExpandArraySpec("0-3,7%2"), (std::vector<int>{0, 1, 2, 3, 7}));
  EXPECT_EQ(ExpandArraySpec("[5-6]"), (std::vector<int>{5, 6}));
  EXPECT_THROW(ArraySpec({}), Error);
  for (const char* bad : {"", "a", "3-1", "1-5:2", "-1", "2.batch"}) {
    EXPECT_THROW(ExpandArraySpec(bad), Error) << bad;
  }
}

TEST(SchedulerLinesTest, SqueueAndSacctLinesGiveEachTaskItsLatestState) {
  std::map<int, TaskState> tasks;
  // squeue -t all -o "%i|%T|%r": a finished task, a running one, pending ones as a range.
  ParseSchedulerLines(
      "7_0|COMPLETED|None\n7_1|CANCELLED|None\n7_[2-3%2]|PENDING|JobArrayTaskLimit\n"
      "9_1|RUNNING|None\n",
      {"7", "9"}, tasks);
  ASSERT_EQ(tasks.size(), 4u);
  EXPECT_EQ(tasks[1].state, "RUNNING");  // the resubmission (job 9) replaces job 7's state
  EXPECT_EQ(tasks[1].job_id, "9");
  EXPECT_EQ(tasks[3].state, "PENDING");
  EXPECT_TRUE(tasks[3].Active());
  EXPECT_FALSE(tasks[0].Active());
  // sacct -n -P -X -o JobID,State,ExitCode: "CANCELLED by 1000", steps skipped.
  tasks.clear();
  ParseSchedulerLines("12_4|CANCELLED by 1000|0:15\n12_4.batch|CANCELLED|0:15\n12|FAILED|1:0\n",
                      {"12"}, tasks);
  ASSERT_EQ(tasks.size(), 1u);
  EXPECT_EQ(tasks[4].state, "CANCELLED");
  EXPECT_EQ(tasks[4].reason, "0:15");
}

TEST(SbatchScriptTest, ScriptNamesTheInstalledBinaryTheJobDirectoryAndEveryOptionGiven) {
  SbatchOptions options;
  options.brdfrig = "/opt/brdfrig 0.1/bin/brdfrig";
  options.partition = "lab";
  options.time = "0-02:00:00";
  options.mem_per_task = "4G";
  options.cpus_per_task = 2;
  options.throttle = 8;
  const JobDir dir("/srv/jobs/2026-11");
  const std::string script = SbatchScript(options, dir, 12);
  for (const char* line : {"#!/bin/bash\n", "#SBATCH --array=0-11%8\n", "#SBATCH --partition=lab\n",
                           "#SBATCH --time=0-02:00:00\n", "#SBATCH --mem=4G\n",
                           "#SBATCH --cpus-per-task=2\n", "#SBATCH --chdir=/srv/jobs/2026-11\n",
                           "#SBATCH --output=/srv/jobs/2026-11/logs/%A_%a.out\n",
                           "exec '/opt/brdfrig 0.1/bin/brdfrig' batch run /srv/jobs/2026-11\n"}) {
    EXPECT_NE(script.find(line), std::string::npos) << line << "\n" << script;
  }
  const fs::path file = fs::temp_directory_path() / "sbatch_script_test.sbatch";
  std::ofstream(file) << script;
  EXPECT_EQ(ScriptThrottle(file), 8);

  options.mem_per_task.clear();
  options.partition.clear();
  const std::string plain = SbatchScript(options, dir, 1);
  EXPECT_EQ(plain.find("--mem"), std::string::npos);
  EXPECT_EQ(plain.find("--partition"), std::string::npos);
}

TEST(SbatchScriptTest, OptionsSayWhichFieldIsWrong) {
  const auto message = [](const SbatchOptions& o) {
    try {
      o.Validate();
    } catch (const OptionsError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  SbatchOptions options;
  options.brdfrig = "/usr/bin/brdfrig";
  EXPECT_EQ(message(options), "");
  SbatchOptions relative = options;
  relative.brdfrig = "build/brdfrig";
  EXPECT_NE(message(relative).find("SbatchOptions.brdfrig = "), std::string::npos);
  SbatchOptions time = options;
  time.time = "2 hours";
  EXPECT_NE(message(time).find("SbatchOptions.time = 2 hours"), std::string::npos);
  SbatchOptions mem = options;
  mem.mem_per_task = "4GB";
  EXPECT_NE(message(mem).find("SbatchOptions.mem_per_task = 4GB"), std::string::npos);
  SbatchOptions throttle = options;
  throttle.throttle = -1;
  EXPECT_NE(message(throttle).find("SbatchOptions.throttle = -1"), std::string::npos);
}

TEST(TaskIndexTest, ComesFromSlurmArrayTaskIdAndIsRefusedWhenMissingOrNotANumber) {
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  EXPECT_THROW(TaskIndexFromEnvironment(), Error);
  ::setenv("SLURM_ARRAY_TASK_ID", "17", 1);
  EXPECT_EQ(TaskIndexFromEnvironment(), 17);
  ::setenv("SLURM_ARRAY_TASK_ID", "4294967294x", 1);
  EXPECT_THROW(TaskIndexFromEnvironment(), Error);
  // Issue 25, finding 11: strtol's leading blanks and sign are not what Slurm sets.
  for (const char* id : {" 3", "+3", "-3", "3 ", "0x3", "99999999999"}) {
    ::setenv("SLURM_ARRAY_TASK_ID", id, 1);
    EXPECT_THROW(TaskIndexFromEnvironment(), Error) << '"' << id << '"';
  }
  ::unsetenv("SLURM_ARRAY_TASK_ID");
}

// Issue 25, finding 11: `--index=-1` was taken as "no --index" and blamed the environment.
TEST(TaskIndexTest, NegativeIndexOptionIsRefusedAsAnIndex) {
  ::unsetenv("SLURM_ARRAY_TASK_ID");
  const auto result = brdfrig::testing::RunBrdfrig("batch run /nonexistent-job --index=-1");
  EXPECT_NE(result.status, 0) << result.output;
  EXPECT_NE(result.output.find("--index -1: an item index is >= 0"), std::string::npos)
      << result.output;
  EXPECT_EQ(result.output.find("SLURM_ARRAY_TASK_ID"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace brdfrig::batch
