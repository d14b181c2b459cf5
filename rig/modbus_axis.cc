#include "rig/modbus_axis.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <thread>

#include "common/angles.h"
#include "common/format.h"

namespace brdfrig::rig {
namespace {

std::string DegreesText(double radians) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.3f deg", brdfrig::Degrees(radians));
  return text;
}

std::string Number(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", value);
  return text;
}

}  // namespace

void ModbusAxisOptions::Validate() const {
  if (slave < 1 || slave > 247) throw OptionsError("modbus axis: slave must be 1..247");
  if (!(steps_per_degree > 0)) throw OptionsError("modbus axis: steps_per_degree must be > 0");
  if (!(min_deg < max_deg)) throw OptionsError("modbus axis: min_deg must be below max_deg");
  if (!(speed_deg_s > 0)) throw OptionsError("modbus axis: speed_deg_s must be > 0");
  if (!(acceleration_deg_s2 > 0)) throw OptionsError("modbus axis: accel_deg_s2 must be > 0");
  if (move_timeout.count() <= 0) throw OptionsError("modbus axis: move_timeout must be > 0");
  if (poll_interval.count() <= 0) throw OptionsError("modbus axis: poll_ms must be > 0");
  if (tolerance_steps < 0) throw OptionsError("modbus axis: tolerance_steps must be >= 0");
}

ModbusAxisOptions ReadModbusAxisOptions(const YamlNode& settings) {
  ModbusAxisOptions o;
  if (const auto n = settings.Optional("slave"))
    o.slave = static_cast<int>(n->InRange(n->AsInt(), 1, 247));
  if (const auto n = settings.Optional("steps_per_degree"))
    o.steps_per_degree = n->Positive(n->AsDouble());
  if (const auto n = settings.Optional("min_deg")) o.min_deg = n->AsDouble();
  if (const auto n = settings.Optional("max_deg")) {
    o.max_deg = n->AsDouble();
    if (!(o.min_deg < o.max_deg)) n->Fail("max_deg must be above min_deg");
  }
  if (const auto n = settings.Optional("speed_deg_s")) o.speed_deg_s = n->Positive(n->AsDouble());
  if (const auto n = settings.Optional("accel_deg_s2")) {
    o.acceleration_deg_s2 = n->Positive(n->AsDouble());
  }
  if (const auto n = settings.Optional("move_timeout_s")) {
    o.move_timeout = std::chrono::milliseconds(std::llround(1000 * n->Positive(n->AsDouble())));
  }
  if (const auto n = settings.Optional("poll_ms")) {
    o.poll_interval = std::chrono::milliseconds(static_cast<int>(n->InRange(n->AsInt(), 1, 10000)));
  }
  if (const auto n = settings.Optional("tolerance_steps")) {
    o.tolerance_steps = static_cast<int>(n->InRange(n->AsInt(), 0, 1000000));
  }
  return o;
}

ModbusAxis::ModbusAxis(std::string name, std::shared_ptr<ModbusLink> link, DriveProfile profile,
                       ModbusAxisOptions options)
    : name_(std::move(name)),
      link_(std::move(link)),
      profile_(std::move(profile)),
      options_(options) {
  options_.Validate();
}

std::string ModbusAxis::Describe() const {
  return "modbus " + link_->options().Endpoint() + " slave " + std::to_string(options_.slave) +
         ", profile " + profile_.name;
}

std::string ModbusAxis::Settings() const {
  return Number(options_.steps_per_degree) + " steps/deg, limits " + Number(options_.min_deg) +
         ".." + Number(options_.max_deg) + " deg, " + Number(options_.speed_deg_s) + " deg/s, " +
         Number(options_.acceleration_deg_s2) + " deg/s^2";
}

double ModbusAxis::ToRadians(int32_t steps) const {
  return Radians(steps / options_.steps_per_degree);
}

DriveReading ModbusAxis::Read() {
  // Status, alarm code and position in one request when they are close together (AZ: 80
  // registers apart), which halves the polling traffic on a slow RS-485 bus.
  const int lo = std::min({profile_.status, profile_.alarm_code, profile_.position_readback});
  const int hi = std::max({profile_.status, profile_.alarm_code, profile_.position_readback}) + 2;
  std::map<int, int32_t> values;
  if (hi - lo <= 125) {
    const std::vector<uint16_t> words = link_->ReadRegisters(options_.slave, lo, hi - lo);
    for (int address : {profile_.status, profile_.alarm_code, profile_.position_readback}) {
      values[address] = UnpackValue(profile_, &words[static_cast<std::size_t>(address - lo)]);
    }
  } else {
    for (int address : {profile_.status, profile_.alarm_code, profile_.position_readback}) {
      values[address] =
          UnpackValue(profile_, link_->ReadRegisters(options_.slave, address, 2).data());
    }
  }
  const auto status = static_cast<uint32_t>(values[profile_.status]);
  auto bit = [status](int b) { return ((status >> b) & 1u) != 0; };
  DriveReading r;
  r.ready = bit(profile_.ready_bit);
  r.moving = bit(profile_.moving_bit);
  r.in_position = bit(profile_.in_position_bit);
  r.alarm = bit(profile_.alarm_bit);
  r.home_end = profile_.home_end_bit ? bit(*profile_.home_end_bit) : true;
  r.alarm_code = values[profile_.alarm_code];
  r.position_steps = values[profile_.position_readback];
  return r;
}

void ModbusAxis::WriteMove(int32_t target_steps) {
  std::map<int, int32_t> block;  // address -> value, written in address order
  block[profile_.position] = target_steps;
  block[profile_.speed] = static_cast<int32_t>(
      std::max(1L, std::lround(options_.speed_deg_s * options_.steps_per_degree)));
  const auto accel = static_cast<int32_t>(
      std::max(1L, std::lround(options_.acceleration_deg_s2 * options_.steps_per_degree)));
  block[profile_.acceleration] = accel;
  if (profile_.deceleration) block[*profile_.deceleration] = accel;
  for (const RegisterValue& c : profile_.constants) block[c.address] = c.value;

  // Contiguous runs go in one Write Multiple Registers each. The trigger goes last: appended to
  // the block when the block is one run ending just below it (a drive applies one request as a
  // whole, AZ direct data operation expects exactly that), otherwise in a request of its own.
  std::vector<std::pair<int, std::vector<uint16_t>>> runs;
  for (const auto& [address, value] : block) {
    if (runs.empty() ||
        runs.back().first + static_cast<int>(runs.back().second.size()) != address) {
      runs.emplace_back(address, std::vector<uint16_t>{});
    }
    uint16_t words[2];
    PackValue(profile_, value, words);
    runs.back().second.insert(runs.back().second.end(), words, words + 2);
  }
  uint16_t trigger[2];
  PackValue(profile_, profile_.trigger.value, trigger);
  const auto& last = runs.back();
  if (runs.size() == 1 &&
      last.first + static_cast<int>(last.second.size()) == profile_.trigger.address) {
    runs.back().second.insert(runs.back().second.end(), trigger, trigger + 2);
  } else {
    runs.emplace_back(profile_.trigger.address, std::vector<uint16_t>(trigger, trigger + 2));
  }
  for (const auto& [address, words] : runs) link_->WriteRegisters(options_.slave, address, words);
}

void ModbusAxis::PulseCommand(int bit) {
  std::vector<uint16_t> words(2);
  PackValue(profile_, static_cast<int32_t>(1u << bit), words.data());
  link_->WriteRegisters(options_.slave, profile_.command, words);
  PackValue(profile_, 0, words.data());
  link_->WriteRegisters(options_.slave, profile_.command, words);
}

void ModbusAxis::Fail(AxisError::Kind kind, int alarm_code, const std::string& message) {
  std::string stop_note;
  try {
    Stop();
    stop_note = "the drive was stopped";
  } catch (const Error& e) {
    stop_note = std::string("the stop command FAILED as well (") + e.what() +
                "): check the drive before moving anything";
  }
  throw AxisError(kind, alarm_code, name_ + ": " + message + "; " + stop_note);
}

template <typename Done>
DriveReading ModbusAxis::WaitFor(const std::string& what,
                                 std::chrono::steady_clock::time_point deadline, Done done) {
  while (true) {
    const DriveReading r = Read();
    if (r.alarm) {
      Fail(AxisError::Kind::kAlarm, r.alarm_code,
           "drive alarm " + Hex(r.alarm_code) + " during " + what + " (at " +
               DegreesText(ToRadians(r.position_steps)) +
               "); see the drive manual's alarm table, fix the cause, then reset the alarm");
    }
    if (done(r)) return r;
    if (std::chrono::steady_clock::now() > deadline) {
      Fail(AxisError::Kind::kTimeout, 0,
           what + " did not finish within " + Number(options_.move_timeout.count() / 1000.0) +
               " s (now at " + DegreesText(ToRadians(r.position_steps)) +
               (r.moving ? ", still moving" : ", not moving") + ")");
    }
    std::this_thread::sleep_for(options_.poll_interval);
  }
}

MoveReport ModbusAxis::MoveTo(double angle) {
  const double deg = Degrees(angle);
  if (!(deg >= options_.min_deg && deg <= options_.max_deg)) {
    throw AxisError(AxisError::Kind::kLimits, 0,
                    name_ + ": " + DegreesText(angle) + " is outside the configured limits [" +
                        Number(options_.min_deg) + ", " + Number(options_.max_deg) +
                        "] deg; nothing was moved");
  }
  const auto target = static_cast<int32_t>(std::lround(deg * options_.steps_per_degree));
  const auto start = std::chrono::steady_clock::now();
  try {
    WriteMove(target);
    const DriveReading r = WaitFor(
        "move to " + DegreesText(angle), start + options_.move_timeout, [&](const DriveReading& s) {
          return !s.moving && s.in_position &&
                 std::abs(s.position_steps - target) <= options_.tolerance_steps;
        });
    MoveReport report;
    report.position = ToRadians(r.position_steps);
    report.duration_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
  } catch (const ModbusError& e) {
    Fail(AxisError::Kind::kCommunication, 0,
         std::string("move to ") + DegreesText(angle) + ": " + e.what());
  }
}

void ModbusAxis::Home() {
  const auto start = std::chrono::steady_clock::now();
  try {
    PulseCommand(profile_.home_bit);
    WaitFor("homing", start + options_.move_timeout,
            [](const DriveReading& s) { return !s.moving && s.in_position && s.home_end; });
  } catch (const ModbusError& e) {
    Fail(AxisError::Kind::kCommunication, 0, std::string("homing: ") + e.what());
  }
}

AxisStatus ModbusAxis::Status() {
  AxisStatus status;
  try {
    const DriveReading r = Read();
    status.position = ToRadians(r.position_steps);
    status.alarm_code = r.alarm ? r.alarm_code : 0;
    status.state = r.alarm ? AxisState::kAlarm : r.moving ? AxisState::kMoving : AxisState::kReady;
    status.message = r.alarm ? "alarm " + Hex(r.alarm_code) : r.moving ? "moving" : "ready";
  } catch (const ModbusError& e) {
    status.state = AxisState::kDisconnected;
    status.message = e.what();
  }
  return status;
}

void ModbusAxis::Stop() {
  try {
    PulseCommand(profile_.stop_bit);
  } catch (const ModbusError& e) {
    throw AxisError(AxisError::Kind::kCommunication, 0, name_ + ": stop: " + e.what());
  }
}

void ModbusAxis::ResetAlarm() {
  try {
    PulseCommand(profile_.alarm_reset_bit);
  } catch (const ModbusError& e) {
    throw AxisError(AxisError::Kind::kCommunication, 0, name_ + ": alarm reset: " + e.what());
  }
}

}  // namespace brdfrig::rig
