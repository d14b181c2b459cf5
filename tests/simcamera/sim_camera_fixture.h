// A simulated PTP/IP camera on a loopback port for the tests: the default scene at 160×120
// seen by an ideal sensor (no noise, so brightness ratios are exact), the axes where the test
// puts them, and a private HOME for libgphoto2's settings file (~/.gphoto/settings holds the
// PTP/IP GUID).
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <sstream>
#include <string>

#include "sim/scene.h"
#include "simcamera/ptpip_server.h"
#include "simcamera/shot_renderer.h"

namespace brdfrig::simcamera {

inline sim::Scene SmallTestScene() {
  std::ifstream in(std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/ggx.yaml");
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = yaml.find(from);
    if (at == std::string::npos) throw std::runtime_error("ggx.yaml changed: " + from);
    yaml.replace(at, from.size(), to);
  };
  replace("resolution: [1600, 1200]", "resolution: [160, 120]");
  replace("supersampling: 4", "supersampling: 1");
  return sim::LoadSceneString(yaml, "small default scene").Ideal();
}

class SimCameraTest : public ::testing::Test {
 protected:
  void SetUp() override {
    home_ = std::filesystem::temp_directory_path() /
            ("brdfrig_simcamera_" + std::to_string(getpid()) + "_" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(home_);
    std::filesystem::create_directories(home_);
    setenv("HOME", home_.c_str(), 1);
    renderer_ = std::make_shared<ShotRenderer>(
        SmallTestScene(),
        [this] {
          std::lock_guard lock(positions_mutex_);
          return positions_;
        },
        2);
    CameraServerOptions options;
    options.offer.shutter_speeds_s = {1.0 / 1000, 1.0 / 250, 1.0 / 60, 1.0 / 15};
    options.offer.initial.exposure_s = 1.0 / 250;
    server_ = std::make_unique<PtpIpCameraServer>(
        options, [renderer = renderer_](const ExposureSettings& e) { return renderer->Shoot(e); });
  }
  void TearDown() override {
    server_.reset();
    std::filesystem::remove_all(home_);
  }

  void SetPositions(geometry::AxisPositions positions) {
    std::lock_guard lock(positions_mutex_);
    positions_ = std::move(positions);
  }

  std::filesystem::path home_;
  std::shared_ptr<ShotRenderer> renderer_;
  std::unique_ptr<PtpIpCameraServer> server_;
  std::mutex positions_mutex_;
  geometry::AxisPositions positions_;
};

}  // namespace brdfrig::simcamera
