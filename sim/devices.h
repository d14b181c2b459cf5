// Simulated devices implementing the rig interfaces on top of a shared SimWorld, and their
// registration as the "sim" backend. Device settings in rig.yaml:
//
//   camera:    {backend: sim, scene: scenes/default.yaml, truth_dir: truth}   (truth optional)
//   light_arm: {backend: sim, scene: scenes/default.yaml, axis: light_arm}    (axis defaults
//                                                                               to the device name)
//   lamp:      {backend: sim, scene: scenes/default.yaml}
//
// Paths are relative to the rig file's directory. Devices naming the same scene share a world.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <tuple>

#include "rig/axis.h"
#include "rig/camera.h"
#include "sim/world.h"

namespace brdfrig::sim {

class SimCamera : public rig::Camera {
 public:
  // `truth_dir`: when set, every shot also writes <frame>.json (true geometry) and, for each
  // new pose, the true radiance as an EXR there — for evaluation, apart from the photos.
  SimCamera(std::shared_ptr<SimWorld> world, std::filesystem::path truth_dir = {}, int threads = 0);

  rig::CameraInfo Info() const override;
  double SetExposure(double seconds) override;
  std::vector<rig::Frame> Capture() override;
  void Reopen() override;

 private:
  std::shared_ptr<SimWorld> world_;
  std::filesystem::path truth_dir_;
  int threads_;
  // The last pose's radiance, reused across a bracket (only the exposure changes).
  std::optional<std::tuple<geometry::AxisPositions, bool, int>> cached_key_;
  cv::Mat cached_radiance_;
  std::string cached_radiance_file_;
};

class SimAxis : public rig::Axis {
 public:
  SimAxis(std::shared_ptr<SimWorld> world, std::string axis);
  std::string Name() const override { return axis_; }
  void Home() override;
  rig::MoveReport MoveTo(double angle) override;
  rig::AxisStatus Status() override;
  void Stop() override {}  // moves complete within MoveTo
  void ResetAlarm() override;

 private:
  std::shared_ptr<SimWorld> world_;
  std::string axis_;
};

class SimLight : public rig::Light {
 public:
  explicit SimLight(std::shared_ptr<SimWorld> world) : world_(std::move(world)) {}
  void SetOn(bool on) override { world_->SetLightOn(on); }

 private:
  std::shared_ptr<SimWorld> world_;
};

// Registers the "sim" camera, axis and light backends with rig/backend_registry.h.
void RegisterSimBackends();

}  // namespace brdfrig::sim
