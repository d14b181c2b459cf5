// Drive profiles: the shipped ones load, bad ones are errors naming file:line, and rig.yaml
// settings for the modbus backend are checked the same way.
#include "rig/drive_profile.h"

#include <gtest/gtest.h>

#include "common/error.h"
#include "rig/backend_registry.h"
#include "rig/hardware_backends.h"
#include "rig/modbus_link.h"

namespace brdfrig::rig {
namespace {

std::string ErrorOf(const std::string& yaml) {
  try {
    ParseDriveProfile(LoadYamlString(yaml, "bad.yaml"));
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

const char* kGeneric = R"(profile: t
word_order: high_first
move: {position: 0, speed: 2, acceleration: 4, trigger: {address: 6, value: 1}}
status: {address: 8, bits: {ready: 0, moving: 1, in_position: 2, alarm: 3}}
alarm_code: 10
position_readback: 12
command: {address: 14, bits: {stop: 0, home: 1, alarm_reset: 2}}
)";

TEST(DriveProfileTest, ShippedProfilesLoad) {
  const DriveProfile az = LoadDriveProfile("oriental_az_direct");
  EXPECT_EQ(az.position, 0x5C);
  EXPECT_EQ(az.trigger.address, 0x66);
  EXPECT_EQ(az.alarm_bit, 7);
  EXPECT_EQ(az.constants.size(), 3u);
  EXPECT_TRUE(az.deceleration.has_value());
  const DriveProfile generic = LoadDriveProfile("generic");
  EXPECT_EQ(generic.status, 8);
  EXPECT_FALSE(generic.deceleration.has_value());
}

TEST(DriveProfileTest, WordOrderRoundTripsNegativeValues) {
  DriveProfile p;
  for (bool high_first : {true, false}) {
    p.high_word_first = high_first;
    uint16_t words[2];
    PackValue(p, -123456, words);
    EXPECT_EQ(UnpackValue(p, words), -123456);
  }
  p.high_word_first = true;
  uint16_t words[2];
  PackValue(p, 0x00012345, words);
  EXPECT_EQ(words[0], 0x0001);
  EXPECT_EQ(words[1], 0x2345);
}

TEST(DriveProfileTest, BadWordOrderUnknownKeyAndOverlapNameTheLine) {
  std::string text = kGeneric;
  text.replace(text.find("high_first"), 10, "middle");
  EXPECT_NE(ErrorOf(text).find("bad.yaml:2:"), std::string::npos) << ErrorOf(text);

  EXPECT_NE(ErrorOf(std::string(kGeneric) + "colour: red\n").find("bad.yaml:8:"),
            std::string::npos);

  text = kGeneric;
  text.replace(text.find("alarm_code: 10"), 14, "alarm_code: 13");
  EXPECT_NE(ErrorOf(text).find("register 13"), std::string::npos) << ErrorOf(text);

  text = kGeneric;
  text.replace(text.find("alarm: 3"), 8, "alarm: 40");
  EXPECT_NE(ErrorOf(text).find("bad.yaml:4:"), std::string::npos) << ErrorOf(text);
}

TEST(DriveProfileTest, UnknownProfileNameIsAnError) {
  EXPECT_THROW(LoadDriveProfile("no_such_drive"), Error);
}

std::string AxisErrorOf(const std::string& yaml) {
  RegisterHardwareBackends();
  const YamlNode settings = LoadYamlString(yaml, "rig.yaml");
  try {
    CreateAxis("modbus", settings, {"light_arm", "/tmp"});
  } catch (const FileError& e) {
    return e.what();
  }
  return "no error";
}

TEST(ModbusSettingsTest, BadTransportUnknownKeyAndMissingProfileNameTheLine) {
  EXPECT_NE(AxisErrorOf("transport: udp\nhost: x\nprofile: generic\n").find("rig.yaml:1:"),
            std::string::npos);
  EXPECT_NE(AxisErrorOf("transport: tcp\nhost: 127.0.0.1\nprofile: generic\nspeed: 3\n")
                .find("rig.yaml:4:"),
            std::string::npos);
  EXPECT_NE(AxisErrorOf("transport: tcp\nhost: 127.0.0.1\nprofile: nope\n").find("rig.yaml:3:"),
            std::string::npos);
  EXPECT_NE(AxisErrorOf("transport: rtu\ndevice: /dev/x\nparity: maybe\nprofile: generic\n")
                .find("rig.yaml:3:"),
            std::string::npos);
  EXPECT_NE(AxisErrorOf("transport: tcp\nhost: h\nprofile: generic\nmin_deg: 10\nmax_deg: 5\n")
                .find("rig.yaml:5:"),
            std::string::npos);
}

// A profile name too long for the file system to look up is "not found", not an exception
// from <filesystem> (the same bug fuzz_rig_yaml found in rig.yaml's geometry name).
TEST(DriveProfileTest, UnlookableNameIsNotFound) {
  try {
    LoadDriveProfile(std::string(300, 'p'), "");
    FAIL() << "an unlookable profile name was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::rig
