// A drive's Modbus register map, read from a profile file (rig/profiles/*.yaml) so that a new
// drive is a new file, not new code. Every value is 32 bits wide (two holding registers);
// `word_order` says which word comes first. The same profile drives the client (ModbusAxis)
// and the simulated drive server (sim/modbus_drive_server.h), so both agree by construction.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "common/yaml_reader.h"

namespace brdfrig::rig {

struct RegisterValue {
  int address = 0;
  int32_t value = 0;
};

struct DriveProfile {
  std::string name;
  std::string description;
  std::filesystem::path file;
  bool high_word_first = true;

  // Move: target position (steps), speed (steps/s), acceleration/deceleration (steps/s^2).
  int position = 0;
  int speed = 0;
  int acceleration = 0;
  std::optional<int> deceleration;       // absent: the drive uses `acceleration` for both
  RegisterValue trigger;                 // written last; the drive starts when it takes the value
  std::vector<RegisterValue> constants;  // fixed values written with every move

  // Status word bits (bit numbers within the 32-bit status value).
  int status = 0;
  int ready_bit = 0;
  int moving_bit = 0;
  int in_position_bit = 0;
  int alarm_bit = 0;
  std::optional<int> home_end_bit;

  int alarm_code = 0;         // register holding the present alarm code
  int position_readback = 0;  // register holding the measured position, steps

  // Command word: bits are pulsed (set, then cleared) to stop, home and reset alarms.
  int command = 0;
  int stop_bit = 0;
  int home_bit = 0;
  int alarm_reset_bit = 0;

  // Highest register address the profile uses (+1 for the second word).
  int HighestRegister() const;
};

// Loads a profile; errors are FileError with file:line. `name_or_path` is either a path to a
// .yaml file or the name of a shipped profile (e.g. "oriental_az_direct", "generic"), looked
// up in `search_dir` and then in the source tree's rig/profiles.
DriveProfile LoadDriveProfile(const std::string& name_or_path,
                              const std::filesystem::path& search_dir = {});
DriveProfile ParseDriveProfile(const YamlNode& root);

// The directory of the profiles shipped with the source tree.
std::filesystem::path ShippedProfileDir();

// 32-bit values <-> register pairs in the profile's word order.
void PackValue(const DriveProfile& profile, int32_t value, uint16_t* words);
int32_t UnpackValue(const DriveProfile& profile, const uint16_t* words);

}  // namespace brdfrig::rig
