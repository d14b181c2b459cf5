// Photos of a scene's printed board taken the way `brdfrig simulate` takes them: the simulated
// camera device (render, sensor effects, the scene's photo format), decoded as a photo file is.
#pragma once

#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "calibrate/lens_calibration.h"
#include "sim/devices.h"
#include "sim/world.h"

namespace brdfrig::calibrate::testing {

inline std::vector<CalibrationPhoto> SimulatedBoardPhotos(const sim::Scene& scene,
                                                          const std::vector<int>& poses) {
  auto world = std::make_shared<sim::SimWorld>(scene);
  sim::SimCamera camera(world, {}, 0);
  std::vector<CalibrationPhoto> photos;
  for (int pose : poses) {
    world->SetBoardPose(pose);
    camera.SetExposure(scene.board->exposure_s);
    const std::vector<rig::Frame> frames = camera.Capture();
    const std::vector<std::byte>& bytes = frames.front().bytes;
    cv::Mat encoded(1, static_cast<int>(bytes.size()), CV_8U, const_cast<std::byte*>(bytes.data()));
    photos.push_back({"board_" + std::to_string(pose) + scene.sensor.Extension(),
                      cv::imdecode(encoded, cv::IMREAD_UNCHANGED | cv::IMREAD_ANYDEPTH)});
  }
  return photos;
}

// The same camera at half the resolution (same field of view): a quarter of the rendering, for
// tests whose claim does not depend on the pixel count.
inline sim::Scene HalfResolution(sim::Scene scene) {
  geometry::Intrinsics& k = scene.rig.intrinsics;
  k.width /= 2;
  k.height /= 2;
  k.fx *= 0.5;
  k.fy *= 0.5;
  k.cx = 0.5 * (k.cx + 0.5) - 0.5;  // pixel centres at integers on both grids
  k.cy = 0.5 * (k.cy + 0.5) - 0.5;
  return scene;
}

inline std::string ChArUcoScenePath() {
  return std::string(BRDFRIG_SOURCE_DIR) + "/sim/scenes/charuco_board.yaml";
}

}  // namespace brdfrig::calibrate::testing
