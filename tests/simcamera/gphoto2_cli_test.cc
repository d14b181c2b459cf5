// Debian's unmodified `gphoto2` tool against the simulated PTP/IP camera: a second client,
// independent of ours, that lists the settings, sets them and captures RAW+JPEG through
// libgphoto2's ptp2 driver. What it downloads is checked for content, not only existence.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>

#include "reconstruct/raw_photo.h"
#include "sim_camera_fixture.h"
#include "tests/simcamera/ptpip_test_client.h"

namespace brdfrig::simcamera {
namespace {

struct ToolRun {
  int status = -1;
  std::string output;
};

class Gphoto2ToolTest : public SimCameraTest {
 protected:
  // Runs gphoto2 on the simulated camera in the test's HOME and directory, LANG=C.
  ToolRun Gphoto2(const std::string& arguments) {
    const std::string command = "cd '" + home_.string() + "' && env LANG=C HOME='" +
                                home_.string() + "' timeout 60 gphoto2 --port " +
                                server_->PortPath() + " --camera 'PTP/IP Camera' " + arguments +
                                " 2>&1";
    ToolRun run;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return run;
    char buffer[4096];
    while (std::fgets(buffer, sizeof buffer, pipe) != nullptr) run.output += buffer;
    const int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (run.status == 127) {
      ADD_FAILURE() << "the gphoto2 tool is not installed (Debian package gphoto2, listed in "
                       "scripts/packages.txt)";
    }
    return run;
  }

  // Captures one RAW+JPEG pair at `shutter` into shot_N.* and returns the JPEG and DNG paths.
  std::pair<std::filesystem::path, std::filesystem::path> CapturePair(const std::string& shutter,
                                                                      const std::string& tag) {
    const ToolRun run =
        Gphoto2("--set-config shutterspeed=" + shutter +
                " --capture-image-and-download --wait-event-and-download=1s --filename '" + tag +
                "_%n.%C'");
    EXPECT_EQ(run.status, 0) << run.output;
    std::filesystem::path jpeg, dng;
    for (const auto& entry : std::filesystem::directory_iterator(home_)) {
      const std::string name = entry.path().filename().string();
      if (name.rfind(tag + "_", 0) != 0) continue;
      if (entry.path().extension() == ".JPG") jpeg = entry.path();
      if (entry.path().extension() == ".DNG") dng = entry.path();
    }
    return {jpeg, dng};
  }
};

double MeanOf(const cv::Mat& image) {
  const cv::Scalar m = cv::mean(image);
  return (m[0] + m[1] + m[2]) / 3;
}

TEST_F(Gphoto2ToolTest, SummaryNamesTheSimulatedBodyAndItsCard) {
  const ToolRun run = Gphoto2("--summary");
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Model: brdfrig PTP/IP simulated camera"), std::string::npos)
      << run.output;
  EXPECT_NE(run.output.find("Capture Formats: JPEG DNG"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("store_00010001"), std::string::npos) << run.output;
}

// Issue 25, finding 9: one idle connection opened just before made the camera wait 5 s for its
// first packet, and `gphoto2 --summary` fail with an I/O error (libgphoto2 waits 2.5 s).
TEST_F(Gphoto2ToolTest, SummaryWorksWhileAnIdleConnectionIsOpen) {
  const int idle = testing::ConnectTo(server_->port());
  ASSERT_GE(idle, 0);
  const ToolRun run = Gphoto2("--summary");
  close(idle);
  ASSERT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("Model: brdfrig PTP/IP simulated camera"), std::string::npos)
      << run.output;
}

TEST_F(Gphoto2ToolTest, ListsShutterSpeedIsoAndFNumberAsItsStandardWidgets) {
  const ToolRun list = Gphoto2("--list-config");
  ASSERT_EQ(list.status, 0) << list.output;
  for (const char* widget : {"/main/capturesettings/shutterspeed", "/main/imgsettings/iso",
                             "/main/capturesettings/f-number"}) {
    EXPECT_NE(list.output.find(widget), std::string::npos) << widget << "\n" << list.output;
  }
  const ToolRun shutter = Gphoto2("--get-config shutterspeed");
  ASSERT_EQ(shutter.status, 0) << shutter.output;
  EXPECT_NE(shutter.output.find("Type: RADIO"), std::string::npos) << shutter.output;
  EXPECT_NE(shutter.output.find("Current: 0.0040s"), std::string::npos) << shutter.output;
  EXPECT_NE(shutter.output.find("Choice: 3 0.0667s"), std::string::npos) << shutter.output;
}

TEST_F(Gphoto2ToolTest, SettingsSetByTheToolAreTheCamerasExposure) {
  const ToolRun run =
      Gphoto2("--set-config shutterspeed=1/60 --set-config iso=400 --set-config f-number=f/5.6");
  ASSERT_EQ(run.status, 0) << run.output;
  const ExposureSettings e = server_->exposure();
  EXPECT_NEAR(e.exposure_s, 0.0167, 1e-9);  // 1/60 s in PTP's 0.1 ms units
  EXPECT_EQ(e.iso, 400);
  EXPECT_NEAR(e.f_number, 5.6, 1e-9);
  const ToolRun read = Gphoto2("--get-config iso");
  EXPECT_NE(read.output.find("Current: 400"), std::string::npos) << read.output;
}

TEST_F(Gphoto2ToolTest, CapturesRawJpegPairsWhoseSignalFollowsTheShutterSpeed) {
  SetPositions({{"camera_arm", 0.3}, {"light_arm", -0.3}});
  const auto [jpeg_short, dng_short] = CapturePair("1/1000", "short");
  const auto [jpeg_long, dng_long] = CapturePair("1/250", "long");
  ASSERT_FALSE(jpeg_short.empty());
  ASSERT_FALSE(dng_short.empty());
  ASSERT_FALSE(jpeg_long.empty());
  ASSERT_FALSE(dng_long.empty());

  const cv::Mat jpeg = cv::imread(jpeg_long.string(), cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(jpeg.empty()) << "not a JPEG OpenCV can read";
  EXPECT_EQ(jpeg.type(), CV_8UC3);
  EXPECT_EQ(jpeg.cols, 160);
  EXPECT_EQ(jpeg.rows, 120);

  // The DNG is linear: four times the exposure gives four times the signal wherever the
  // long exposure did not clip (the highlight does), to within 16-bit rounding.
  const cv::Mat raw_short = reconstruct::ReadRawPhoto(dng_short);
  const cv::Mat raw_long = reconstruct::ReadRawPhoto(dng_long);
  ASSERT_EQ(raw_long.cols, 160);
  ASSERT_EQ(raw_long.rows, 120);
  // Per-value ratios on well-exposed values: dim ones carry 16-bit rounding and LibRaw's
  // conversion to sRGB primaries clamps at 0, both of which bias a plain sum.
  std::vector<double> ratios;
  for (int y = 0; y < raw_long.rows; ++y) {
    for (int i = 0; i < raw_long.cols * 3; ++i) {
      const double s = raw_short.ptr<std::uint16_t>(y)[i];
      const double l = raw_long.ptr<std::uint16_t>(y)[i];
      if (l < 65000 && s >= 1000) ratios.push_back(l / s);
    }
  }
  ASSERT_GT(ratios.size(), 1000u) << "too few well-exposed values to compare";
  std::nth_element(ratios.begin(), ratios.begin() + ratios.size() / 2, ratios.end());
  EXPECT_NEAR(ratios[ratios.size() / 2], 4.0, 0.01);
  double max_long = 0;
  cv::minMaxLoc(raw_long.reshape(1), nullptr, &max_long);
  // (LibRaw's trip through the colour matrices rounds full scale to 65533..65535.)
  EXPECT_GE(max_long, 65000) << "the specular highlight of the mirror pose should clip";
  // The JPEG is the same shot in sRGB: brighter with the longer exposure, not linear.
  const cv::Mat jpeg_dark = cv::imread(jpeg_short.string(), cv::IMREAD_UNCHANGED);
  EXPECT_GT(MeanOf(jpeg), 1.5 * MeanOf(jpeg_dark));
  EXPECT_LT(MeanOf(jpeg), 4.0 * MeanOf(jpeg_dark));
  // gphoto2 deletes what it downloaded with --capture-image-and-download.
  EXPECT_EQ(server_->counters().captures, 2);
}

}  // namespace
}  // namespace brdfrig::simcamera
