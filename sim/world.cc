#include "sim/world.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>

#include "common/angles.h"
#include "common/error.h"
#include "sim/pixel_rng.h"

namespace brdfrig::sim {
namespace {

using rig::AxisError;
using rig::CameraError;

// FNV-1a: a stable stream id per axis name (std::hash may differ between standard libraries).
std::uint64_t StableHash(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (const char c : text) h = (h ^ static_cast<unsigned char>(c)) * 0x100000001b3ull;
  return h;
}

std::string DegreesText(double radians) {
  std::ostringstream out;
  out << brdfrig::Degrees(radians) << "°";
  return out.str();
}

}  // namespace

SimWorld::SimWorld(Scene scene) : simulator_(std::move(scene)) {
  for (const geometry::RotationAxis& axis : simulator_.scene().rig.axes) axes_[axis.name] = {};
  for (const SimFault& fault : simulator_.scene().faults) {
    if (fault.type == SimFault::Type::kCameraBusy) busy_left_[fault.at] += fault.count;
  }
  const SensorDescription& sensor = simulator_.scene().sensor;
  exposure_s_ = sensor.shutter_speeds.empty()
                    ? std::clamp(0.01, sensor.min_exposure_s, sensor.max_exposure_s)
                    : sensor.shutter_speeds.front();
}

std::shared_ptr<SimWorld> SimWorld::Shared(const std::filesystem::path& scene_path) {
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<SimWorld>> worlds;
  std::error_code ec;
  std::filesystem::path key = std::filesystem::weakly_canonical(scene_path, ec);
  if (ec) key = std::filesystem::absolute(scene_path);
  std::lock_guard lock(mutex);
  if (auto existing = worlds[key.string()].lock()) return existing;
  auto world = std::make_shared<SimWorld>(LoadScene(scene_path));
  worlds[key.string()] = world;
  return world;
}

SimWorld::AxisState& SimWorld::State(const std::string& axis) {
  const auto it = axes_.find(axis);
  if (it == axes_.end()) {
    throw AxisError(AxisError::Kind::kOther, 0, "no axis named '" + axis + "' in the scene");
  }
  return it->second;
}

const SimWorld::AxisState& SimWorld::State(const std::string& axis) const {
  return const_cast<SimWorld*>(this)->State(axis);
}

void SimWorld::AdvanceLocked(double seconds, std::unique_lock<std::mutex>& lock) {
  clock_s_ += seconds;
  const double factor = scene().timing.real_time_factor;
  if (factor > 0 && seconds > 0) {
    // Sleep without the lock, as a real device would be busy without blocking the others.
    lock.unlock();
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds * factor));
    lock.lock();
  }
}

// Trapezoidal velocity profile; a triangle when the move is too short to reach full speed.
double SimWorld::MoveDuration(const std::string& axis, double distance) const {
  const AxisTiming& t = scene().timing.For(axis);
  const double d = std::abs(distance);
  if (d * t.acceleration <= t.speed * t.speed) return 2.0 * std::sqrt(d / t.acceleration);
  return d / t.speed + t.speed / t.acceleration;
}

rig::MoveReport SimWorld::MoveAxis(const std::string& axis, double commanded) {
  std::unique_lock lock(mutex_);
  AxisState& state = State(axis);
  const geometry::RotationAxis& geometry = *scene().rig.FindAxis(axis);
  if (state.alarm) {
    throw AxisError(AxisError::Kind::kAlarm, state.alarm_code,
                    "axis '" + axis + "' is in alarm; reset it first");
  }
  if (!std::isfinite(commanded) || commanded < geometry.min - 1e-9 ||
      commanded > geometry.max + 1e-9) {
    throw AxisError(AxisError::Kind::kLimits, 0,
                    "axis '" + axis + "': target " + DegreesText(commanded) + " is outside [" +
                        DegreesText(geometry.min) + ", " + DegreesText(geometry.max) + "]");
  }
  ++state.moves;
  for (std::size_t i = 0; i < scene().faults.size(); ++i) {
    const SimFault& f = scene().faults[i];
    if (f.type == SimFault::Type::kAxisAlarm && f.axis == axis && f.at == state.moves &&
        !fired_[i]) {
      fired_[i] = true;
      state.alarm = true;
      state.alarm_code = f.alarm_code;
      throw AxisError(AxisError::Kind::kAlarm, f.alarm_code,
                      "axis '" + axis + "': drive alarm " + std::to_string(f.alarm_code) +
                          " during move " + std::to_string(state.moves) + " (scheduled fault)");
    }
  }
  const double distance = commanded - state.commanded;
  if (distance != 0) state.direction = distance > 0 ? 1 : -1;
  state.commanded = commanded;
  state.actual = commanded;
  if (const auto& mech = scene().effects.mechanical_error) {
    // The arm lags behind the motor by half the backlash, on the side it came from.
    state.actual -= state.direction * 0.5 * mech->backlash;
    if (mech->jitter > 0) {
      PixelRng rng(scene().render.seed, static_cast<std::uint64_t>(state.moves), StableHash(axis),
                   0);
      state.actual += mech->jitter * rng.Gaussian();
    }
  }
  const double duration = MoveDuration(axis, distance);
  AdvanceLocked(duration, lock);
  return {state.commanded, duration};
}

void SimWorld::HomeAxis(const std::string& axis) {
  std::unique_lock lock(mutex_);
  AxisState& state = State(axis);
  if (state.alarm) {
    throw AxisError(AxisError::Kind::kAlarm, state.alarm_code,
                    "axis '" + axis + "' is in alarm; reset it first");
  }
  const double duration = MoveDuration(axis, state.commanded);
  // Homing finds the reference switch: the arm is exactly at 0 afterwards.
  state.commanded = state.actual = 0;
  state.direction = 0;
  AdvanceLocked(duration, lock);
}

rig::AxisStatus SimWorld::AxisStatus(const std::string& axis) const {
  std::lock_guard lock(mutex_);
  const AxisState& state = State(axis);
  rig::AxisStatus status;
  status.position = state.commanded;
  if (state.alarm) {
    status.state = rig::AxisState::kAlarm;
    status.alarm_code = state.alarm_code;
    status.message = "alarm " + std::to_string(state.alarm_code);
  }
  return status;
}

void SimWorld::ResetAxisAlarm(const std::string& axis) {
  std::lock_guard lock(mutex_);
  AxisState& state = State(axis);
  state.alarm = false;
  state.alarm_code = 0;
}

geometry::AxisPositions SimWorld::TruePositions() const {
  std::lock_guard lock(mutex_);
  geometry::AxisPositions positions;
  for (const auto& [name, state] : axes_) positions[name] = state.actual;
  return positions;
}

double SimWorld::SetExposure(double seconds) {
  std::lock_guard lock(mutex_);
  if (!camera_connected_) throw CameraError(CameraError::Kind::kGone, 0, "camera disconnected");
  const SensorDescription& sensor = scene().sensor;
  if (!(seconds > 0) || !std::isfinite(seconds)) {
    throw CameraError(CameraError::Kind::kBadSettings, 0,
                      "exposure must be positive, got " + std::to_string(seconds));
  }
  if (sensor.shutter_speeds.empty()) {
    exposure_s_ = std::clamp(seconds, sensor.min_exposure_s, sensor.max_exposure_s);
  } else {
    // Nearest in log space, as photographers count stops.
    exposure_s_ = *std::min_element(
        sensor.shutter_speeds.begin(), sensor.shutter_speeds.end(), [&](double a, double b) {
          return std::abs(std::log(a / seconds)) < std::abs(std::log(b / seconds));
        });
  }
  return exposure_s_;
}

ShotTicket SimWorld::BeginShot() {
  std::unique_lock lock(mutex_);
  if (!camera_connected_) throw CameraError(CameraError::Kind::kGone, 0, "camera disconnected");
  const int number = shots_ + 1;
  for (std::size_t i = 0; i < scene().faults.size(); ++i) {
    const SimFault& f = scene().faults[i];
    if (f.type == SimFault::Type::kCameraDisconnect && f.at == shots_ && !fired_[i]) {
      fired_[i] = true;
      camera_connected_ = false;
      reopen_failures_left_ = f.count;
      throw CameraError(
          CameraError::Kind::kGone, 0,
          "camera disconnected after " + std::to_string(shots_) + " shots (scheduled fault)");
    }
  }
  if (auto busy = busy_left_.find(number); busy != busy_left_.end() && busy->second > 0) {
    --busy->second;
    throw CameraError(CameraError::Kind::kBusy, 0,
                      "camera busy at shot " + std::to_string(number) + " (scheduled fault)");
  }
  shots_ = number;
  const Scene& s = scene();
  ShotTicket ticket;
  ticket.number = number;
  ticket.exposure_s = exposure_s_;
  ticket.light_on = light_on_;
  ticket.board_pose = board_pose_;
  for (const auto& [name, state] : axes_) ticket.true_positions[name] = state.actual;
  ticket.exposure_duration_s = exposure_s_ + s.timing.shot_overhead_s;
  ticket.download_duration_s = s.timing.download_s;
  for (const SimFault& f : s.faults) {
    if (f.type == SimFault::Type::kSlowDownload && number >= f.at && number < f.at + f.count) {
      ticket.download_duration_s = f.duration_s;
    }
  }
  AdvanceLocked(ticket.exposure_duration_s, lock);
  return ticket;
}

void SimWorld::FinishShot(const ShotTicket& ticket) {
  std::unique_lock lock(mutex_);
  AdvanceLocked(ticket.download_duration_s, lock);
}

void SimWorld::ReopenCamera() {
  std::unique_lock lock(mutex_);
  if (!camera_connected_) {
    if (reopen_failures_left_ > 0) {
      --reopen_failures_left_;
      AdvanceLocked(scene().timing.reopen_s, lock);
      throw CameraError(CameraError::Kind::kNotFound, 0, "no camera found (simulated disconnect)");
    }
    camera_connected_ = true;
  }
  AdvanceLocked(scene().timing.reopen_s, lock);
}

int SimWorld::shots() const {
  std::lock_guard lock(mutex_);
  return shots_;
}

void SimWorld::SetLightOn(bool on) {
  std::lock_guard lock(mutex_);
  light_on_ = on;
}

void SimWorld::SetBoardPose(int pose) {
  const int poses = scene().board ? static_cast<int>(scene().board->world_from_page.size()) : 0;
  if (pose < 0 || pose >= poses) {
    throw Error("board pose " + std::to_string(pose) + ": the scene's board has " +
                std::to_string(poses) + " poses");
  }
  std::lock_guard lock(mutex_);
  board_pose_ = pose;
}

double SimWorld::virtual_time_s() const {
  std::lock_guard lock(mutex_);
  return clock_s_;
}

}  // namespace brdfrig::sim
