// The sharded reconstruction on a real Slurm: a private single-node cluster (munge, slurmctld,
// slurmd on loopback, all in a temporary directory) runs `brdfrig batch` job arrays over
// simulated sessions. Every material.json must be byte for byte the local batch run's; a task
// killed mid-way must be reported by collect and completed by its resubmission; the daemon's
// hand-off must bring a captured session to its material unattended.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <thread>

#include "acquire/daemon.h"
#include "batch/job_dir.h"
#include "common/atomic_file.h"
#include "common/subprocess.h"
#include "reconstruct/batch.h"
#include "sim/devices.h"
#include "tests/batch/private_slurm.h"
#include "tests/common/run_brdfrig.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::batch {
namespace {

namespace fs = std::filesystem;
using brdfrig::testing::RunBrdfrig;

// Small sessions (two positions at 320×240) of three different materials: enough to make a
// task run for seconds, so that it can be killed while it works.
constexpr std::array<const char*, 3> kSessions = {"s1", "s2", "s3"};
constexpr std::array<const char*, 3> kMaterials = {
    "{model: ggx, alpha: 0.10, f0: 0.8, diffuse: 0.10}",
    "{model: ggx, alpha: 0.15, f0: 0.6, diffuse: 0.20}",
    "{model: ggx, alpha: 0.08, f0: 0.9, diffuse: 0.05}"};

class SlurmArrayTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    skip_reason_ = new std::string;
    start_error_ = new std::string;
    const std::string missing = testing::PrivateSlurm::MissingPrograms();
    if (!missing.empty()) {
      *skip_reason_ = "Slurm is not installed here (missing: " + missing +
                      "); scripts/setup.sh installs slurm-wlm and munge";
      return;
    }
    root_ = new fs::path(fs::temp_directory_path() / "slurm_array_test");
    fs::remove_all(*root_);
    fs::create_directories(*root_ / "archive");
    for (std::size_t i = 0; i < kSessions.size(); ++i) {
      reconstruct::testing::SceneSpec spec;
      spec.brdf = kMaterials[i];
      spec.width = 320;
      spec.height = 240;
      spec.supersampling = 2;
      spec.positions = "[{camera_arm: 25, light_arm: -25}, {camera_arm: 45, light_arm: -45}]";
      reconstruct::testing::SimulateCapture(*root_ / "work" / kSessions[i], spec);
      fs::rename(*root_ / "work" / kSessions[i] / "capture", *root_ / "archive" / kSessions[i]);
    }
    // The reference: the local batch run. One rung (ggx) keeps the test quick, and proves the
    // manifest carries the settings: a task fitting the whole ladder would differ.
    const auto start = std::chrono::steady_clock::now();
    const brdfrig::testing::CommandResult local =
        RunBrdfrig("reconstruct " + (*root_ / "archive").string() + " -o " +
                   (*root_ / "local").string() + " -j 2 --model ggx");
    std::printf("local batch of %zu sessions: %.1f s\n", kSessions.size(),
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    ASSERT_EQ(local.status, 0) << local.output;
    try {
      slurm_ = testing::PrivateSlurm::Start().release();
    } catch (const std::exception& e) {
      *start_error_ = e.what();  // installed but not running: a failure, with the logs
    }
  }

  static void TearDownTestSuite() {
    delete slurm_;
    slurm_ = nullptr;
  }

  void SetUp() override {
    if (!skip_reason_->empty()) GTEST_SKIP() << *skip_reason_;
    ASSERT_NE(slurm_, nullptr) << "the private Slurm did not start: " << *start_error_;
  }

  // `brdfrig batch prepare` of the archive into job directory `name`, fits into `name`_fits,
  // two tasks at a time; returns the submitted array job's id.
  static std::string PrepareAndSubmit(const std::string& name) {
    const brdfrig::testing::CommandResult prepared =
        RunBrdfrig("batch prepare " + (*root_ / "archive").string() + " -o " +
                   (*root_ / (name + "_fits")).string() + " --job-dir " + (*root_ / name).string() +
                   " --throttle 2 --time 10:00 --model ggx --submit");
    EXPECT_EQ(prepared.status, 0) << prepared.output;
    const std::vector<Submission> submissions = ReadSubmissions(JobDir(*root_ / name));
    EXPECT_EQ(submissions.size(), 1u) << prepared.output;
    return submissions.empty() ? "" : submissions.front().job_id;
  }

  static void ExpectMaterialsAsLocal(const std::string& fits) {
    for (const char* session : kSessions) {
      const fs::path material = *root_ / fits / session / "material.json";
      ASSERT_TRUE(fs::exists(material)) << material;
      EXPECT_EQ(ReadFileToString(material),
                ReadFileToString(*root_ / "local" / session / "material.json"))
          << material << " differs from the local batch run's";
    }
  }

  static brdfrig::testing::CommandResult WaitFor(const std::string& job) {
    return RunBrdfrig("batch status " + (*root_ / job).string() + " --wait --interval 0.2");
  }

  static std::string* skip_reason_;
  static std::string* start_error_;
  static fs::path* root_;
  static testing::PrivateSlurm* slurm_;
};

std::string* SlurmArrayTest::skip_reason_ = nullptr;
std::string* SlurmArrayTest::start_error_ = nullptr;
fs::path* SlurmArrayTest::root_ = nullptr;
testing::PrivateSlurm* SlurmArrayTest::slurm_ = nullptr;

TEST_F(SlurmArrayTest, ArrayWritesEveryMaterialByteForByteAsTheLocalBatch) {
  const auto start = std::chrono::steady_clock::now();
  ASSERT_FALSE(PrepareAndSubmit("whole").empty());
  const brdfrig::testing::CommandResult waited = WaitFor("whole");
  ASSERT_EQ(waited.status, 0) << waited.output;
  std::printf("Slurm array of %zu sessions: %.1f s\n", kSessions.size(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  const brdfrig::testing::CommandResult collected =
      RunBrdfrig("batch collect " + (*root_ / "whole").string());
  EXPECT_EQ(collected.status, 0) << collected.output << slurm_->LogTails();
  EXPECT_NE(collected.output.find("3 succeeded"), std::string::npos) << collected.output;
  ExpectMaterialsAsLocal("whole_fits");
}

TEST_F(SlurmArrayTest, CollectReportsAKilledTaskAndItsResubmissionCompletesIt) {
  const std::string job = PrepareAndSubmit("killed");
  ASSERT_FALSE(job.empty());
  // Kill task 1 once it is at work: its log shows the reconstruction's first progress line.
  const fs::path log = *root_ / "killed" / "logs" / (job + "_1.out");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (std::chrono::steady_clock::now() < deadline &&
         (!fs::exists(log) || ReadFileToString(log).find("merging") == std::string::npos)) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_NE(ReadFileToString(log).find("merging"), std::string::npos) << "task 1 never started";
  const ProcessResult cancelled = RunProcess({"scancel", job + "_1"});
  ASSERT_TRUE(cancelled.ok()) << cancelled.err;
  WaitFor("killed");
  // Nothing half-written: no result, no material for the killed item.
  EXPECT_FALSE(fs::exists(JobDir(*root_ / "killed").result(1)));
  EXPECT_FALSE(fs::exists(*root_ / "killed_fits" / "s2" / "material.json"));

  brdfrig::testing::CommandResult collected =
      RunBrdfrig("batch collect " + (*root_ / "killed").string() + " --resubmit");
  EXPECT_EQ(collected.status, 1) << collected.output;
  EXPECT_NE(collected.output.find("NO RESULT  1 "), std::string::npos) << collected.output;
  EXPECT_NE(collected.output.find("CANCELLED"), std::string::npos) << collected.output;
  EXPECT_NE(collected.output.find("2 succeeded"), std::string::npos) << collected.output;
  EXPECT_NE(collected.output.find("submitted job"), std::string::npos) << collected.output;
  const std::vector<Submission> submissions = ReadSubmissions(JobDir(*root_ / "killed"));
  ASSERT_EQ(submissions.size(), 2u);
  EXPECT_EQ(submissions[1].array, "1%2");  // only the killed item, with the script's throttle

  WaitFor("killed");
  collected = RunBrdfrig("batch collect " + (*root_ / "killed").string());
  EXPECT_EQ(collected.status, 0) << collected.output << slurm_->LogTails();
  EXPECT_NE(collected.output.find("3 succeeded"), std::string::npos) << collected.output;
  ExpectMaterialsAsLocal("killed_fits");
}

TEST_F(SlurmArrayTest, DaemonHandsEachCompleteSessionToTheClusterUnattended) {
  // The acquisition daemon on a simulated rig, configured to hand each complete session to
  // `brdfrig batch prepare ... --submit`: capture → Slurm → material.json with nobody acting.
  const fs::path lab = *root_ / "lab";
  fs::create_directories(lab);
  reconstruct::testing::SceneSpec spec;
  spec.brdf = kMaterials[0];
  spec.width = 320;
  spec.height = 240;
  spec.supersampling = 2;
  std::ofstream(lab / "scene.yaml") << reconstruct::testing::SceneYaml(spec);
  std::ofstream(lab / "rig.yaml") << "geometry: scene.yaml\n"
                                     "camera: {backend: sim, scene: scene.yaml}\n"
                                     "axes:\n"
                                     "  camera_arm: {backend: sim, scene: scene.yaml}\n"
                                     "  light_arm: {backend: sim, scene: scene.yaml}\n"
                                     "light: {backend: sim, scene: scene.yaml}\n";
  sim::RegisterSimBackends();
  acquire::DaemonConfig config;
  config.data_dir = lab / "sessions";
  config.rig_file = lab / "rig.yaml";
  char socket_dir[] = "/tmp/brdfrig-sock-XXXXXX";  // sun_path holds 107 bytes
  ASSERT_NE(::mkdtemp(socket_dir), nullptr);
  config.socket = fs::path(socket_dir) / "d.sock";
  config.hand_off.command = {BRDFRIG_BINARY, "batch",
                             "prepare",      "{session}",
                             "-o",           (lab / "fits").string(),
                             "--job-dir",    (lab / "jobs" / "{name}").string(),
                             "--model",      "ggx",
                             "--submit"};
  const std::string plan =
      "sample: tile\npositions:\n  - {camera_arm: 25, light_arm: -25}\n"
      "  - {camera_arm: 45, light_arm: -45}\nexposures: [0.001, 0.008, 0.0666667]\nsettle_s: 0\n";
  {
    acquire::Daemon daemon(config);
    const acquire::HttpResponse submitted = daemon.Handle(
        {"POST", "/v1/sessions", nlohmann::json{{"name", "tile-01"}, {"plan", plan}}.dump(), ""});
    ASSERT_EQ(submitted.status, 201) << submitted.body;
    daemon.WaitIdle();  // the capture and its hand-off (sbatch answered)
  }
  fs::remove_all(socket_dir);
  const JobDir job(lab / "jobs" / "tile-01");
  ASSERT_EQ(ReadSubmissions(job).size(), 1u) << "the daemon handed nothing to Slurm";
  WaitFor("lab/jobs/tile-01");
  const brdfrig::testing::CommandResult collected =
      RunBrdfrig("batch collect " + job.root.string());
  EXPECT_EQ(collected.status, 0) << collected.output;
  // The same session fitted locally: the same bytes.
  const brdfrig::testing::CommandResult local =
      RunBrdfrig("reconstruct " + (config.data_dir / "tile-01").string() + " -o " +
                 (lab / "local").string() + " --model ggx");
  ASSERT_EQ(local.status, 0) << local.output;
  EXPECT_EQ(ReadFileToString(lab / "fits" / "tile-01" / "material.json"),
            ReadFileToString(lab / "local" / "material.json"));
}

}  // namespace
}  // namespace brdfrig::batch
