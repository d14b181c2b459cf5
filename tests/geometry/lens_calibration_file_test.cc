// The lens calibration file: what is written is read back, a damaged file is an error naming
// it, and a calibration of another camera is refused when applied.
#include "geometry/lens_calibration_file.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"

namespace brdfrig::geometry {
namespace {

std::filesystem::path Scratch(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("lens_calibration_file_test_" + name);
}

LensCalibration Example() {
  LensCalibration c;
  c.created = "2026-12-02T10:00:00Z";
  c.software = "brdfrig test";
  c.camera_model = "Nikon DSC D750";
  c.camera_serial = "3012345";
  c.board = {{"type", "charuco"}};
  c.intrinsics = {1600, 1200, 2222.5, 2222.1, 806.4, 593.2, -0.1, 0.05};
  c.uncertainty = {0, 0, 0.5, 0.5, 0.2, 0.3, 0.001, 0.01};
  c.rms_px = 0.07;
  c.coverage = 0.77;
  c.corners = 140;
  c.photos = {{"a.png", 70, 0.06, 2.0}, {"b.png", 70, 0.08, 2.1}};
  return c;
}

TEST(LensCalibrationFileTest, WrittenCalibrationReadsBackUnchanged) {
  const std::filesystem::path path = Scratch("roundtrip.json");
  WriteLensCalibration(path, Example());
  const LensCalibration read = ReadLensCalibration(path);
  EXPECT_EQ(read.camera_model, "Nikon DSC D750");
  EXPECT_EQ(read.camera_serial, "3012345");
  EXPECT_EQ(read.intrinsics.width, 1600);
  EXPECT_DOUBLE_EQ(read.intrinsics.fx, 2222.5);
  EXPECT_DOUBLE_EQ(read.intrinsics.cy, 593.2);
  EXPECT_DOUBLE_EQ(read.intrinsics.k1, -0.1);
  EXPECT_DOUBLE_EQ(read.uncertainty.k2, 0.01);
  ASSERT_EQ(read.photos.size(), 2u);
  EXPECT_EQ(read.photos[1].photo, "b.png");
  EXPECT_DOUBLE_EQ(read.rms_px, 0.07);
}

TEST(LensCalibrationFileTest, DamagedOrImplausibleFileIsAnErrorNamingIt) {
  const std::filesystem::path path = Scratch("damaged.json");
  std::ofstream(path) << R"({"format": "brdfrig-lens-calibration", "version": 1})";
  try {
    ReadLensCalibration(path);
    FAIL() << "expected a FileError";
  } catch (const FileError& e) {
    EXPECT_EQ(e.file(), path.string());
  }
  LensCalibration outside = Example();
  outside.intrinsics.cx = 2000;  // principal point outside the image
  WriteLensCalibration(path, outside);
  EXPECT_THROW(ReadLensCalibration(path), FileError);
}

TEST(LensCalibrationFileTest, CalibrationOfAnotherCameraIsRefused) {
  const LensCalibration c = Example();
  Intrinsics nominal{1600, 1200, 2222.2, 2222.2, 799.5, 599.5, 0, 0};
  const Intrinsics applied = ApplyLensCalibration(c, "lens.json", nominal, "nikon dsc d750");
  EXPECT_DOUBLE_EQ(applied.fx, 2222.5);
  EXPECT_DOUBLE_EQ(applied.k1, -0.1);
  // Another image size: another camera (or another crop or mode of it).
  Intrinsics other_size = nominal;
  other_size.width = 6000;
  other_size.height = 4000;
  try {
    ApplyLensCalibration(c, "lens.json", other_size, "");
    FAIL() << "expected a refusal";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("another camera"), std::string::npos) << e.what();
  }
  // Another model named by the rig.
  EXPECT_THROW(ApplyLensCalibration(c, "lens.json", nominal, "Canon EOS R5"), FileError);
}

}  // namespace
}  // namespace brdfrig::geometry
