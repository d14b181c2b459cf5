#include "rig/drive_profile.h"

#include <algorithm>
#include <set>

#include "common/error.h"

namespace brdfrig::rig {
namespace {

// Modbus addresses are 16 bits and every value takes two registers.
int ReadAddress(const YamlNode& node) {
  const int address = node.AsInt();
  if (address < 0 || address > 0xFFFE) node.Fail("expected a register address 0..65534");
  return address;
}

int ReadBit(const YamlNode& bits, const std::string& key) {
  const YamlNode node = bits.Required(key);
  const int bit = node.AsInt();
  if (bit < 0 || bit > 31) node.Fail("expected a bit number 0..31");
  return bit;
}

RegisterValue ReadRegisterValue(const YamlNode& node) {
  if (!node.IsMap()) node.Fail("expected {address: N, value: V}");
  RegisterValue out;
  out.address = ReadAddress(node.Required("address"));
  out.value = node.Required("value").AsInt();
  node.Finish();
  return out;
}

}  // namespace

int DriveProfile::HighestRegister() const {
  int highest = std::max({position, speed, acceleration, deceleration.value_or(0), trigger.address,
                          status, alarm_code, position_readback, command});
  for (const RegisterValue& c : constants) highest = std::max(highest, c.address);
  return highest + 1;
}

DriveProfile ParseDriveProfile(const YamlNode& root) {
  if (!root.IsMap()) root.Fail("expected a drive profile mapping");
  DriveProfile p;
  p.file = root.file();
  p.name = root.Required("profile").AsString();
  p.description = root.Get("description", "");
  const YamlNode order = root.Required("word_order");
  const std::string word_order = order.AsString();
  if (word_order == "high_first") {
    p.high_word_first = true;
  } else if (word_order == "low_first") {
    p.high_word_first = false;
  } else {
    order.Fail("expected high_first or low_first, got '" + word_order + "'");
  }

  const YamlNode move = root.Required("move");
  p.position = ReadAddress(move.Required("position"));
  p.speed = ReadAddress(move.Required("speed"));
  p.acceleration = ReadAddress(move.Required("acceleration"));
  if (const auto dec = move.Optional("deceleration")) p.deceleration = ReadAddress(*dec);
  p.trigger = ReadRegisterValue(move.Required("trigger"));
  if (const auto constants = move.Optional("constants")) {
    for (const YamlNode& c : constants->Elements()) p.constants.push_back(ReadRegisterValue(c));
  }
  move.Finish();

  const YamlNode status = root.Required("status");
  p.status = ReadAddress(status.Required("address"));
  const YamlNode bits = status.Required("bits");
  p.ready_bit = ReadBit(bits, "ready");
  p.moving_bit = ReadBit(bits, "moving");
  p.in_position_bit = ReadBit(bits, "in_position");
  p.alarm_bit = ReadBit(bits, "alarm");
  if (bits.Has("home_end")) p.home_end_bit = ReadBit(bits, "home_end");
  bits.Finish();
  status.Finish();

  p.alarm_code = ReadAddress(root.Required("alarm_code"));
  p.position_readback = ReadAddress(root.Required("position_readback"));

  const YamlNode command = root.Required("command");
  p.command = ReadAddress(command.Required("address"));
  const YamlNode command_bits = command.Required("bits");
  p.stop_bit = ReadBit(command_bits, "stop");
  p.home_bit = ReadBit(command_bits, "home");
  p.alarm_reset_bit = ReadBit(command_bits, "alarm_reset");
  command_bits.Finish();
  command.Finish();
  root.Finish();

  // Two values sharing a register would silently corrupt each other: reject overlaps, naming
  // the file (the individual nodes are already consumed, so point at the root).
  std::map<int, std::string> used;
  auto claim = [&](int address, const std::string& what) {
    for (int a : {address, address + 1}) {
      const auto [it, inserted] = used.emplace(a, what);
      if (!inserted) {
        root.Fail("register " + std::to_string(a) + " is used by both " + it->second + " and " +
                  what);
      }
    }
  };
  claim(p.position, "move.position");
  claim(p.speed, "move.speed");
  claim(p.acceleration, "move.acceleration");
  if (p.deceleration) claim(*p.deceleration, "move.deceleration");
  claim(p.trigger.address, "move.trigger");
  for (std::size_t i = 0; i < p.constants.size(); ++i) {
    claim(p.constants[i].address, "move.constants[" + std::to_string(i) + "]");
  }
  claim(p.status, "status");
  claim(p.alarm_code, "alarm_code");
  claim(p.position_readback, "position_readback");
  claim(p.command, "command");
  return p;
}

std::filesystem::path ShippedProfileDir() {
  return std::filesystem::path(BRDFRIG_SOURCE_DIR) / "rig" / "profiles";
}

DriveProfile LoadDriveProfile(const std::string& name_or_path,
                              const std::filesystem::path& search_dir) {
  std::vector<std::filesystem::path> candidates;
  const std::filesystem::path given(name_or_path);
  if (given.has_extension()) {
    candidates.push_back(given.is_absolute() || search_dir.empty() ? given : search_dir / given);
  } else {
    if (!search_dir.empty()) candidates.push_back(search_dir / (name_or_path + ".yaml"));
    candidates.push_back(ShippedProfileDir() / (name_or_path + ".yaml"));
  }
  for (const auto& candidate : candidates) {
    std::error_code error;  // a name too long to look up is "not found", not an exception
    if (std::filesystem::exists(candidate, error)) {
      return ParseDriveProfile(LoadYamlFile(candidate.string()));
    }
  }
  std::string tried;
  for (const auto& candidate : candidates) tried += " " + candidate.string();
  throw Error("drive profile '" + name_or_path + "' not found (looked for:" + tried + ")");
}

void PackValue(const DriveProfile& profile, int32_t value, uint16_t* words) {
  const auto u = static_cast<uint32_t>(value);
  const auto high = static_cast<uint16_t>(u >> 16);
  const auto low = static_cast<uint16_t>(u & 0xFFFF);
  words[0] = profile.high_word_first ? high : low;
  words[1] = profile.high_word_first ? low : high;
}

int32_t UnpackValue(const DriveProfile& profile, const uint16_t* words) {
  const uint32_t high = profile.high_word_first ? words[0] : words[1];
  const uint32_t low = profile.high_word_first ? words[1] : words[0];
  return static_cast<int32_t>((high << 16) | low);
}

}  // namespace brdfrig::rig
