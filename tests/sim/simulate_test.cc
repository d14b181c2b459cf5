// `brdfrig simulate` as a library call: a bracketed capture with photos and truth kept apart,
// deterministic to the byte, recovering from the faults a scene schedules.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/atomic_file.h"
#include "sim/image_io.h"
#include "sim/simulate.h"
#include "sim/simulator.h"
#include "test_scene.h"

namespace brdfrig::sim {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = M_PI / 180.0;

class SimulateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("brdfrig_simulate_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path WriteScene(const std::string& extra) {
    std::ofstream(dir_ / "scene.yaml") << testing::BaseSceneYaml() + R"(capture:
  exposures: [0.001, 0.01]
  positions:
    - {camera_arm: 20, light_arm: -20}
    - {camera_arm: 40, light_arm: -40}
effects:
  - {type: shot_noise, full_well: 5000}
  - {type: quantization, bits: 12}
)" + extra;
    return dir_ / "scene.yaml";
  }

  fs::path dir_;
};

TEST_F(SimulateTest, WritesABracketedCaptureWithTruthApart) {
  SimulateOptions options;
  options.scene = WriteScene("");
  options.output_dir = dir_ / "out";
  const SimulateSummary summary = Simulate(options);
  EXPECT_EQ(summary.frames, 4);
  EXPECT_EQ(summary.positions, 2);
  for (const char* name :
       {"p00_e0.png", "p00_e1.png", "p01_e0.png", "p01_e1.png", "capture.json"}) {
    EXPECT_TRUE(fs::exists(dir_ / "out/photos" / name)) << name;
  }
  // Nothing but photos and the rig's log among the photos.
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir_ / "out/photos")) {
    (void)entry;
    ++files;
  }
  EXPECT_EQ(files, 5);
  EXPECT_TRUE(fs::exists(dir_ / "out/truth/p01.exr"));
  EXPECT_TRUE(fs::exists(dir_ / "out/truth/p01.json"));

  // The photo is what the simulator renders at the true position for that shot (frame 4).
  const Simulator simulator(LoadScene(options.scene));
  const geometry::AxisPositions p1 = {{"camera_arm", 40 * kDegree}, {"light_arm", -40 * kDegree}};
  const std::string photo = ReadFileToString(dir_ / "out/photos/p01_e1.png");
  const std::vector<std::byte> expected =
      simulator.EncodePhoto(simulator.RenderCameraImage(p1, 0.01, 4));
  ASSERT_EQ(photo.size(), expected.size());
  EXPECT_EQ(std::memcmp(photo.data(), expected.data(), photo.size()), 0);
  EXPECT_EQ(cv::norm(ReadRadianceExr(dir_ / "out/truth/p01.exr"), simulator.RenderRadiance(p1),
                     cv::NORM_INF),
            0.0);
  const nlohmann::json log =
      nlohmann::json::parse(ReadFileToString(dir_ / "out/photos/capture.json"));
  ASSERT_EQ(log["frames"].size(), 4u);
  EXPECT_NEAR(log["frames"][3]["axis_readings_rad"]["camera_arm"].get<double>(), 40 * kDegree,
              1e-12);
  EXPECT_GT(summary.virtual_time_s, 4 * 1.5);  // at least the downloads
}

TEST_F(SimulateTest, SameSceneGivesIdenticalBytes) {
  SimulateOptions options;
  options.scene = WriteScene("");
  options.output_dir = dir_ / "a";
  options.threads = 1;
  options.write_truth = false;
  Simulate(options);
  options.output_dir = dir_ / "b";
  options.threads = 2;
  Simulate(options);
  for (const char* name : {"p00_e0.png", "p01_e1.png", "capture.json"}) {
    EXPECT_EQ(ReadFileToString(dir_ / "a/photos" / name),
              ReadFileToString(dir_ / "b/photos" / name));
  }
  EXPECT_FALSE(fs::exists(dir_ / "a/truth/p00.exr"));
}

TEST_F(SimulateTest, CommandLinePositionsOverrideTheScene) {
  SimulateOptions options;
  options.scene = WriteScene("");
  options.output_dir = dir_ / "out";
  options.positions = {ParsePositionsDegrees("camera_arm=30,light_arm=-30")};
  options.exposures = {0.005};
  const SimulateSummary summary = Simulate(options);
  EXPECT_EQ(summary.frames, 1);
  const nlohmann::json truth = nlohmann::json::parse(ReadFileToString(dir_ / "out/truth/p00.json"));
  EXPECT_NEAR(truth["axis_positions_rad"]["light_arm"].get<double>(), -30 * kDegree, 1e-12);
}

TEST_F(SimulateTest, AnExposureTheCameraCannotTakeIsTakenAtItsNearestAndSaysSo) {
  SimulateOptions options;
  options.scene = WriteScene("");
  options.output_dir = dir_ / "out";
  options.exposures = {0.01, 4};  // the test scene's shutter speeds end at 0.1 s
  const SimulateSummary summary = Simulate(options);
  ASSERT_EQ(summary.warnings.size(), 1u) << summary.ToString();
  EXPECT_NE(summary.warnings[0].find("asked for a 4 s exposure, the simulated camera took 0.1 s"),
            std::string::npos)
      << summary.warnings[0];
  EXPECT_NE(summary.ToString().find("\nwarning: asked for a 4 s"), std::string::npos);
  const nlohmann::json log =
      nlohmann::json::parse(ReadFileToString(dir_ / "out/photos/capture.json"));
  EXPECT_DOUBLE_EQ(log["frames"][1]["exposure_s"].get<double>(), 0.1);
}

TEST_F(SimulateTest, RecoversFromScheduledFaults) {
  SimulateOptions options;
  options.scene = WriteScene(R"(faults:
  - {type: camera_busy, at_shot: 1, count: 1}
  - {type: camera_disconnect, after_shots: 2, reopen_failures: 1}
  - {type: axis_alarm, axis: light_arm, at_move: 2}
)");
  options.output_dir = dir_ / "out";
  options.write_truth = false;
  const SimulateSummary summary = Simulate(options);
  EXPECT_EQ(summary.frames, 4);
  EXPECT_EQ(summary.recovered_faults, 3);
}

TEST_F(SimulateTest, MissingPositionsIsAClearError) {
  std::ofstream(dir_ / "scene.yaml") << testing::BaseSceneYaml();
  SimulateOptions options;
  options.scene = dir_ / "scene.yaml";
  options.output_dir = dir_ / "out";
  try {
    Simulate(options);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no positions"), std::string::npos);
  }
  EXPECT_THROW(SimulateOptions{}.Validate(), OptionsError);
}

}  // namespace
}  // namespace brdfrig::sim
