// A job directory without a scheduler: the manifest leaves out what is up to date, a task run
// by index writes the local batch run's material and its result, and collect says what
// succeeded, what failed and why, and which items to submit again.
#include <gtest/gtest.h>

#include "batch/collect.h"
#include "batch/prepare.h"
#include "batch/task.h"
#include "common/atomic_file.h"
#include "common/error.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::batch {
namespace {

namespace fs = std::filesystem;

class JobTest : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / "batch_job_test";
    fs::remove_all(root_);
    reconstruct::testing::SceneSpec spec;
    spec.brdf = "{model: ggx, alpha: 0.1, f0: 0.8, diffuse: 0.1}";
    spec.width = 320;
    spec.height = 240;
    spec.supersampling = 2;
    spec.positions = "[{camera_arm: 25, light_arm: -25}, {camera_arm: 45, light_arm: -45}]";
    fs::create_directories(root_ / "archive");
    for (const char* name : {"a", "b"}) {
      reconstruct::testing::SimulateCapture(root_ / "work" / name, spec);
      fs::rename(root_ / "work" / name / "capture", root_ / "archive" / name);
    }
  }

  reconstruct::BatchOptions Options(const fs::path& output) const {
    reconstruct::BatchOptions options;
    options.inputs = {root_ / "archive"};
    options.output = output;
    options.reconstruct.model = "ggx";
    return options;
  }

  fs::path root_;
};

TEST_F(JobTest, ManifestSkipsUpToDateCapturesAndATaskWritesTheLocalBatchMaterial) {
  // Capture a is fitted locally first: up to date, so the job has only b.
  reconstruct::BatchOptions local = Options(root_ / "fits");
  local.inputs = {root_ / "archive" / "a"};
  local.output = root_ / "fits" / "a" / "material.json";
  ASSERT_EQ(reconstruct::BatchExitStatus(reconstruct::ReconstructBatch(local)), 0);

  PrepareOptions prepare;
  prepare.batch = Options(root_ / "fits");
  prepare.sbatch.brdfrig = "/usr/local/bin/brdfrig";
  prepare.job_dir = root_ / "job";
  const Manifest manifest = PrepareJob(prepare);
  ASSERT_EQ(manifest.items.size(), 1u);
  EXPECT_EQ(manifest.items[0].capture, root_ / "archive" / "b");
  ASSERT_EQ(manifest.up_to_date.size(), 1u);
  EXPECT_EQ(manifest.up_to_date[0], root_ / "archive" / "a");
  EXPECT_TRUE(fs::exists(root_ / "job" / "array.sbatch"));
  // Preparing over a job directory would mix two jobs' results.
  EXPECT_THROW(PrepareJob(prepare), FileError);

  const JobDir dir(root_ / "job");
  EXPECT_THROW(RunTask(dir, 1), Error);  // out of range: said, nothing run
  const TaskResult result = RunTask(dir, 0);
  EXPECT_EQ(result.exit_status, 0) << result.item.message;
  const TaskResult recorded = ReadTaskResult(dir.result(0));
  EXPECT_EQ(recorded.exit_status, 0);
  EXPECT_EQ(recorded.item.material_file, root_ / "fits" / "b" / "material.json");

  // The same settings locally give the same bytes.
  reconstruct::BatchOptions again = Options(root_ / "local");
  ASSERT_EQ(reconstruct::BatchExitStatus(reconstruct::ReconstructBatch(again)), 0);
  EXPECT_EQ(ReadFileToString(root_ / "fits" / "b" / "material.json"),
            ReadFileToString(root_ / "local" / "b" / "material.json"));

  const CollectReport report = Collect(dir, {});
  EXPECT_EQ(report.ExitStatus(), 0) << report.Summary();
  EXPECT_TRUE(report.ToResubmit().empty());
}

TEST_F(JobTest, CollectSaysWhyItemsFailedAndResubmitsOnlyFailedAndResultlessOnes) {
  PrepareOptions prepare;
  prepare.batch = Options(root_ / "fits");
  prepare.sbatch.brdfrig = "/usr/local/bin/brdfrig";
  prepare.job_dir = root_ / "job";
  ASSERT_EQ(PrepareJob(prepare).items.size(), 2u);
  const JobDir dir(root_ / "job");
  // Item 0: a failed task (its capture vanished). Item 1: killed, so no result.
  fs::rename(root_ / "archive" / "a", root_ / "a-moved");
  const TaskResult failed = RunTask(dir, 0);
  EXPECT_EQ(failed.exit_status, 1);
  SchedulerView scheduler;
  scheduler.source = "test";
  scheduler.tasks[0] = {"41", "FAILED", "1:0"};
  scheduler.tasks[1] = {"41", "CANCELLED", "0:15"};
  CollectReport report = Collect(dir, scheduler);
  ASSERT_EQ(report.items.size(), 2u);
  EXPECT_EQ(report.items[0].outcome, CollectedItem::Outcome::kFailed);
  EXPECT_NE(report.items[0].why.find("archive/a/capture.json"), std::string::npos)
      << report.items[0].why;
  EXPECT_EQ(report.items[1].outcome, CollectedItem::Outcome::kNoResult);
  EXPECT_NE(report.items[1].why.find("job 41_1 ended CANCELLED (0:15)"), std::string::npos)
      << report.items[1].why;
  EXPECT_EQ(report.ToResubmit(), (std::vector<int>{0, 1}));
  EXPECT_EQ(report.ExitStatus(), 1);
  const std::string summary = report.Summary();
  EXPECT_NE(summary.find("FAILED  0 "), std::string::npos) << summary;
  EXPECT_NE(summary.find("NO RESULT  1 "), std::string::npos) << summary;

  // Resubmitted: item 1 pending again is not submitted a second time, nor counted as done.
  scheduler.tasks[1] = {"43", "PENDING", "Priority"};
  report = Collect(dir, scheduler);
  EXPECT_EQ(report.items[1].outcome, CollectedItem::Outcome::kActive);
  EXPECT_EQ(report.ToResubmit(), (std::vector<int>{0}));
}

// Issue 25, finding 2: two archives' captures of one name were mapped to one material path.
TEST_F(JobTest, TwoCapturesOfOneNameAreRefusedBeforeAnyWork) {
  fs::create_directories(root_ / "other");
  fs::copy(root_ / "archive" / "a", root_ / "other" / "a", fs::copy_options::recursive);
  PrepareOptions prepare;
  prepare.batch = Options(root_ / "fits");
  prepare.batch.inputs.push_back(root_ / "other");
  prepare.sbatch.brdfrig = "/usr/local/bin/brdfrig";
  prepare.job_dir = root_ / "job";
  try {
    (void)PrepareJob(prepare);
    FAIL() << "archive/a and other/a were both prepared";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find((root_ / "other" / "a").string()), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(root_ / "job" / "manifest.json"));
}

// Issue 25, finding 4: a manifest item's material edited to an absolute path elsewhere made the
// task overwrite that file, and results/ replaced by a symlink was followed. Every path taken
// from the job directory stays inside its output and job directories, or the task refuses.
TEST_F(JobTest, ATamperedJobDirectoryCannotMakeATaskWriteOutsideIt) {
  PrepareOptions prepare;
  prepare.batch = Options(root_ / "fits");
  prepare.sbatch.brdfrig = "/usr/local/bin/brdfrig";
  prepare.job_dir = root_ / "job";
  const Manifest manifest = PrepareJob(prepare);
  ASSERT_EQ(manifest.items.size(), 2u);
  const JobDir dir(root_ / "job");
  const std::string original = ReadFileToString(dir.manifest());
  const auto tamper = [&](const fs::path& from, const fs::path& to) {  // every occurrence
    std::string text = original;
    ASSERT_NE(text.find(from.string()), std::string::npos) << from << " in " << text;
    for (std::size_t at = 0; (at = text.find(from.string(), at)) != std::string::npos;) {
      text.replace(at, from.string().size(), to.string());
      at += to.string().size();
    }
    WriteFileAtomically(dir.manifest(), text);
  };
  const auto refused = [&](int index) {
    try {
      (void)RunTask(dir, index);
      ADD_FAILURE() << "item " << index << " ran from a tampered job directory";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(dir.root.string()), std::string::npos) << e.what();
    }
  };
  tamper(root_ / "fits" / "a" / "material.json", root_ / "victim" / "material.json");
  refused(0);
  // The fits directory, consistently, inside capture b: item 0 would write into b's data.
  tamper(root_ / "fits", root_ / "archive" / "b");
  refused(0);
  EXPECT_FALSE(fs::exists(root_ / "victim"));
  EXPECT_FALSE(fs::exists(root_ / "archive" / "b" / "a"));

  WriteFileAtomically(dir.manifest(), original);
  fs::create_directories(root_ / "elsewhere");
  fs::remove_all(dir.results());
  fs::create_directory_symlink(root_ / "elsewhere", dir.results());
  refused(1);
  EXPECT_TRUE(fs::is_empty(root_ / "elsewhere"));
}

// Finding 4: a relative --job-dir run from a directory whose name has a space passed the check
// and wrote a broken #SBATCH --chdir line.
TEST_F(JobTest, ARelativeJobDirIsCheckedAsTheAbsolutePathItNames) {
  const fs::path spaced = root_ / "with space";
  fs::create_directories(spaced);
  const fs::path before = fs::current_path();
  fs::current_path(spaced);
  PrepareOptions prepare;
  prepare.batch = Options(root_ / "fits");
  prepare.sbatch.brdfrig = "/usr/local/bin/brdfrig";
  prepare.job_dir = "job";
  EXPECT_THROW(prepare.Validate(), OptionsError);
  fs::current_path(before);
}

// Issue 25, finding 5: a results/<i>.json nested 200,000 arrays deep crashed collect (the
// reader copied the value); now a FileError naming the file, like any malformed result.
TEST(TaskResultTest, TooDeepResultIsAFileErrorNamingTheFile) {
  const fs::path file = fs::temp_directory_path() / "batch_deep_result.json";
  TaskResult result;
  result.index = 0;
  result.item.status = reconstruct::BatchItem::Status::kDone;
  std::string text = SerializeTaskResult(result);
  const std::string empty = "\"degraded\": []";
  const std::size_t degraded = text.find(empty);
  ASSERT_NE(degraded, std::string::npos) << text;
  text.replace(degraded, empty.size(),
               "\"degraded\": " + std::string(200000, '[') + std::string(200000, ']'));
  WriteFileAtomically(file, text);
  try {
    (void)ReadTaskResult(file);
    FAIL() << "a 200,000 deep result was read";
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), file.string());
    EXPECT_NE(std::string(e.what()).find("nested more than 64 deep"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::batch
