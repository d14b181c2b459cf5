// A lab on loopback for tests: the simulated PTP/IP camera and two simulated Modbus TCP drives
// (camera_arm, light_arm, generic profile) in this process, and a rig.yaml that reaches them
// through the hardware backends only (gphoto2 with a ptpip: port, modbus over TCP). The camera
// renders each shot at the positions it reads from the same drives over Modbus.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "acquire/capture.h"
#include "rig/drive_profile.h"
#include "rig/hardware_backends.h"
#include "sim/modbus_drive_server.h"
#include "simcamera/drive_positions.h"
#include "simcamera/ptpip_server.h"
#include "simcamera/shot_renderer.h"

namespace brdfrig::simcamera {

class LoopbackLab {
 public:
  // Writes scene.yaml, plan.yaml and rig.yaml into `dir` (which holds any file the scene
  // names) and starts the devices; HOME becomes `dir` for libgphoto2's settings file.
  LoopbackLab(const std::filesystem::path& dir, const std::string& scene_yaml,
              const std::string& plan_yaml, std::vector<double> shutter_speeds_s)
      : dir_(dir) {
    setenv("HOME", dir_.c_str(), 1);
    rig::RegisterHardwareBackends();
    std::ofstream(dir_ / "scene.yaml") << scene_yaml;
    std::ofstream(dir_ / "plan.yaml") << plan_yaml;
    const rig::DriveProfile profile = rig::LoadDriveProfile("generic");
    for (const char* axis : {"camera_arm", "light_arm"}) {
      drives_[axis] = std::make_unique<sim::ModbusDriveServer>(profile, sim::DriveServerOptions{});
    }
    // The drives' axes connect on their first request, at the first shot, from the rig file.
    renderer_ = std::make_shared<ShotRenderer>(
        sim::LoadScene(dir_ / "scene.yaml"),
        [this] {
          std::lock_guard lock(positions_mutex_);
          if (!positions_) positions_ = std::make_unique<DrivePositions>(dir_ / "rig.yaml");
          return positions_->Read();
        },
        2);
    CameraServerOptions options;
    options.offer.shutter_speeds_s = std::move(shutter_speeds_s);
    camera_ = std::make_unique<PtpIpCameraServer>(
        options, [renderer = renderer_](const ExposureSettings& e) { return renderer->Shoot(e); });
    WriteRig(true);
  }
  ~LoopbackLab() {
    camera_.reset();
    positions_.reset();
  }

  void WriteRig(bool delete_after_download) {
    std::ofstream(dir_ / "rig.yaml")
        << "geometry: scene.yaml\n"
        << "camera: {backend: gphoto2, port: \"" << camera_->PortPath()
        << "\", delete_after_download: " << (delete_after_download ? "true" : "false")
        << ", event_drain_s: 0.5, timeout_s: 20}\n"
        << "axes:\n"
        << DriveLine("camera_arm") << DriveLine("light_arm");
  }

  acquire::CaptureSummary Capture(const std::string& name) {
    acquire::CaptureOptions options;
    options.rig_file = dir_ / "rig.yaml";
    options.plan_file = dir_ / "plan.yaml";
    options.output_dir = dir_ / "sessions" / name;
    options.run.retry.initial_backoff_s = 0.3;
    return acquire::RunCapture(options);
  }

  PtpIpCameraServer& camera() { return *camera_; }
  const ShotRenderer& renderer() const { return *renderer_; }
  std::filesystem::path session(const std::string& name) const { return dir_ / "sessions" / name; }

 private:
  std::string DriveLine(const std::string& axis) const {
    return "  " + axis + ": {backend: modbus, transport: tcp, host: 127.0.0.1, port: " +
           std::to_string(drives_.at(axis)->port()) +
           ", slave: 1, profile: generic, steps_per_degree: 100, speed_deg_s: 400, "
           "accel_deg_s2: 4000}\n";
  }

  std::filesystem::path dir_;
  std::map<std::string, std::unique_ptr<sim::ModbusDriveServer>> drives_;
  std::mutex positions_mutex_;
  std::unique_ptr<DrivePositions> positions_;
  std::shared_ptr<ShotRenderer> renderer_;
  std::unique_ptr<PtpIpCameraServer> camera_;
};

}  // namespace brdfrig::simcamera
