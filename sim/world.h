// The state the simulated devices of one scene share: where every axis truly is, whether the
// light is on, the camera's shot counter and connection, scheduled faults, and a virtual clock.
// SimCamera, SimAxis and SimLight (sim/devices.h) are thin views of one SimWorld; devices
// configured with the same scene file share one world, so the camera renders with the current
// positions of the sim axes. Thread-safe: devices may be driven from different threads.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "geometry/rig_geometry.h"
#include "rig/axis.h"
#include "rig/camera.h"
#include "sim/simulator.h"

namespace brdfrig::sim {

// What a camera needs to take one shot, decided atomically by the world.
struct ShotTicket {
  int number = 0;  // 1-based shot count (also the noise frame index)
  double exposure_s = 0;
  geometry::AxisPositions true_positions;
  bool light_on = true;
  int board_pose = 0;  // the scene board's pose at the shot (ignored without a board)
  double exposure_duration_s = 0;
  double download_duration_s = 0;
};

class SimWorld {
 public:
  explicit SimWorld(Scene scene);

  // One world per scene file (by canonical path) while any device holds it.
  static std::shared_ptr<SimWorld> Shared(const std::filesystem::path& scene_path);

  const Simulator& simulator() const { return simulator_; }
  const Scene& scene() const { return simulator_.scene(); }

  // --- axes (angles in radians). Throw rig::AxisError for limits and alarms.
  rig::MoveReport MoveAxis(const std::string& axis, double commanded);
  void HomeAxis(const std::string& axis);
  rig::AxisStatus AxisStatus(const std::string& axis) const;
  void ResetAxisAlarm(const std::string& axis);
  // Where the arms truly are (commanded position plus mechanical error).
  geometry::AxisPositions TruePositions() const;

  // --- camera. Throw rig::CameraError for scheduled faults.
  double SetExposure(double seconds);  // returns the exposure actually used
  ShotTicket BeginShot();              // counts the shot and advances the clock by its exposure
  void FinishShot(const ShotTicket& ticket);  // advances the clock by the download
  void ReopenCamera();
  int shots() const;

  // --- light.
  void SetLightOn(bool on);

  // --- the scene's printed board (scene `board:`): which of its poses it is held at, as an
  // operator moves it between shots. Throws Error for a pose the scene does not list.
  void SetBoardPose(int pose);

  // Virtual time since the world was created (seconds). In real-time mode every operation
  // also sleeps real_time_factor × its duration.
  double virtual_time_s() const;

 private:
  struct AxisState {
    double commanded = 0;  // what the drive's encoder reports
    double actual = 0;     // where the arm is
    int direction = 0;     // sign of the last move (backlash side); 0 after homing
    int moves = 0;
    bool alarm = false;
    int alarm_code = 0;
  };

  AxisState& State(const std::string& axis);
  const AxisState& State(const std::string& axis) const;
  void AdvanceLocked(double seconds, std::unique_lock<std::mutex>& lock);
  double MoveDuration(const std::string& axis, double distance) const;

  Simulator simulator_;
  mutable std::mutex mutex_;
  std::map<std::string, AxisState> axes_;
  double clock_s_ = 0;
  bool light_on_ = true;
  int board_pose_ = 0;
  double exposure_s_ = 0.01;
  int shots_ = 0;
  bool camera_connected_ = true;
  int reopen_failures_left_ = 0;
  std::map<int, int> busy_left_;       // shot number -> busy answers still to give
  std::map<std::size_t, bool> fired_;  // fault index -> already happened
};

}  // namespace brdfrig::sim
