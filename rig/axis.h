// A motorized rotation axis (light arm, camera arm, sample tilt, turntable). Angles in radians.
#pragma once

#include <string>

#include "common/error.h"

namespace brdfrig::rig {

enum class AxisState { kReady, kMoving, kAlarm, kDisconnected };

struct AxisStatus {
  AxisState state = AxisState::kReady;
  double position = 0;  // radians, as read back from the drive
  int alarm_code = 0;   // drive's alarm code when state == kAlarm
  std::string message;  // human-readable detail
};

struct MoveReport {
  double position = 0;    // position read back after the move (radians)
  double duration_s = 0;  // how long the move took (device clock; virtual for the sim)
};

class AxisError : public Error {
 public:
  enum class Kind { kAlarm, kTimeout, kLimits, kCommunication, kOther };
  AxisError(Kind kind, int alarm_code, const std::string& message)
      : Error(message), kind_(kind), alarm_code_(alarm_code) {}
  Kind kind() const { return kind_; }
  int alarm_code() const { return alarm_code_; }

 private:
  Kind kind_;
  int alarm_code_;
};

class Axis {
 public:
  virtual ~Axis() = default;
  virtual std::string Name() const = 0;
  virtual void Home() = 0;
  // Moves to an absolute angle and waits until in position. On any failure the axis is
  // stopped before AxisError is thrown.
  virtual MoveReport MoveTo(double angle) = 0;
  virtual AxisStatus Status() = 0;
  virtual void Stop() = 0;
  // Clears an alarm if the drive allows it.
  virtual void ResetAlarm() = 0;
};

class Light {
 public:
  virtual ~Light() = default;
  virtual void SetOn(bool on) = 0;
};

}  // namespace brdfrig::rig
