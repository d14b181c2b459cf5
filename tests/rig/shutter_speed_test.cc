// Shutter-speed labels of different makers parse to seconds; the nearest offered one wins.
#include "rig/shutter_speed.h"

#include <gtest/gtest.h>

#include "common/error.h"

namespace brdfrig::rig {
namespace {

TEST(ShutterSpeedTest, ParsesCanonNikonAndSonyLabels) {
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed("1/60"), 1.0 / 60);     // everyone
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed("0.3"), 0.3);           // Canon
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed("30"), 30);             // Canon, Nikon
  EXPECT_NEAR(*ParseShutterSpeed("0.0166s"), 0.0166, 1e-12);  // older Nikon
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed("30\""), 30);           // Sony
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed("1\"3"), 1.3);          // Sony/Pentax 1.3 s
  EXPECT_DOUBLE_EQ(*ParseShutterSpeed(" 1/4000 "), 1.0 / 4000);
  EXPECT_FALSE(ParseShutterSpeed("bulb"));
  EXPECT_FALSE(ParseShutterSpeed("Bulb"));
  EXPECT_FALSE(ParseShutterSpeed("auto"));
  EXPECT_FALSE(ParseShutterSpeed("x 200"));
  EXPECT_FALSE(ParseShutterSpeed("1/0"));
  EXPECT_FALSE(ParseShutterSpeed(""));
}

TEST(ShutterSpeedTest, NearestIsMeasuredInStopsAndSkipsNonTimes) {
  const std::vector<std::string> offered = {"bulb", "30", "1", "1/50", "1/60", "1/80", "1/4000"};
  EXPECT_EQ(NearestShutterSpeed(offered, 1.0 / 60), 4);
  EXPECT_EQ(NearestShutterSpeed(offered, 1.0 / 64), 4);
  EXPECT_EQ(NearestShutterSpeed(offered, 1.0 / 70), 5);  // 1/80 is 0.19 stops away, 1/60 0.22
  EXPECT_EQ(NearestShutterSpeed(offered, 2), 2);         // 1 s is one stop away, 30 s ~3.9
  EXPECT_EQ(NearestShutterSpeed(offered, 1e-5), 6);
  EXPECT_EQ(NearestShutterSpeed({"bulb", "auto"}, 1), -1);
}

TEST(ShutterSpeedTest, ExposureTextErrorsSayWhatIsExpected) {
  EXPECT_DOUBLE_EQ(ParseExposureText("1/60"), 1.0 / 60);
  EXPECT_DOUBLE_EQ(ParseExposureText("2s"), 2);
  try {
    ParseExposureText("fast");
    FAIL();
  } catch (const OptionsError& e) {
    EXPECT_NE(std::string(e.what()).find("1/60"), std::string::npos);
  }
}

}  // namespace
}  // namespace brdfrig::rig
