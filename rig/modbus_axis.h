// A rotation axis driven by a Modbus positioning drive whose register map is a DriveProfile.
// A move writes target, speed and acceleration with the trigger last, then polls the status
// until the drive reports in-position at the target, raises an alarm, or the move timeout
// passes. Every failure path tries to stop the drive before throwing AxisError, and the
// message says whether that stop succeeded.
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

#include "rig/axis.h"
#include "rig/drive_profile.h"
#include "rig/modbus_link.h"

namespace brdfrig::rig {

struct ModbusAxisOptions {
  int slave = 1;
  double steps_per_degree = 100;         // drive steps (encoder counts) per degree of the axis
  double min_deg = -180, max_deg = 180;  // software limits, checked before any motion
  double speed_deg_s = 20;
  double acceleration_deg_s2 = 100;
  std::chrono::milliseconds move_timeout{30000};
  std::chrono::milliseconds poll_interval{20};
  int tolerance_steps = 2;  // in-position window around the target
  void Validate() const;    // throws OptionsError
};

// Reads the axis keys of rig.yaml settings (slave, steps_per_degree, min_deg, max_deg,
// speed_deg_s, accel_deg_s2, move_timeout_s, poll_ms, tolerance_steps).
ModbusAxisOptions ReadModbusAxisOptions(const YamlNode& settings);

// One decoded status reading.
struct DriveReading {
  bool ready = false, moving = false, in_position = false, alarm = false, home_end = false;
  int alarm_code = 0;
  int32_t position_steps = 0;
};

class ModbusAxis : public Axis {
 public:
  ModbusAxis(std::string name, std::shared_ptr<ModbusLink> link, DriveProfile profile,
             ModbusAxisOptions options);

  std::string Name() const override { return name_; }
  void Home() override;
  MoveReport MoveTo(double angle) override;
  AxisStatus Status() override;
  void Stop() override;
  void ResetAlarm() override;

  // "modbus tcp://host:port slave 1, profile oriental_az_direct" (for `brdfrig rig check`).
  std::string Describe() const;
  // "100 steps/deg, limits -80..80 deg, 20 deg/s, 100 deg/s^2" (for `brdfrig rig check`).
  std::string Settings() const;
  DriveReading Read();

 private:
  void WriteMove(int32_t target_steps);
  void PulseCommand(int bit);
  // Polls until `done` holds, the drive alarms or the deadline passes (alarm/timeout throw).
  template <typename Done>
  DriveReading WaitFor(const std::string& what, std::chrono::steady_clock::time_point deadline,
                       Done done);
  // Stops the drive (best effort) and throws AxisError saying whether the stop worked.
  [[noreturn]] void Fail(AxisError::Kind kind, int alarm_code, const std::string& message);
  double ToRadians(int32_t steps) const;

  std::string name_;
  std::shared_ptr<ModbusLink> link_;
  DriveProfile profile_;
  ModbusAxisOptions options_;
};

}  // namespace brdfrig::rig
