// rig.yaml's `calibration: {lens: FILE}`: the measured intrinsics replace the geometry's, and a
// calibration of another camera or a missing file is an error at the line that names it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "geometry/lens_calibration_file.h"
#include "rig/rig_file.h"

namespace brdfrig::rig {
namespace {

namespace fs = std::filesystem;

class RigLensCalibrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "rig_lens_calibration_test";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path WriteRig(const std::string& calibration_line) {
    const fs::path rig = dir_ / "rig.yaml";
    std::ofstream(rig) << "geometry: " << BRDFRIG_SOURCE_DIR << "/sim/scenes/default.yaml\n"
                       << "camera: {backend: gphoto2, model: \"Nikon DSC D750\"}\n"
                       << calibration_line << "\n";
    return rig;
  }
  void WriteCalibration(int width, int height, const std::string& model) {
    geometry::LensCalibration c;
    c.created = "2026-12-02T10:00:00Z";
    c.camera_model = model;
    c.intrinsics = {width, height, 2230.0, 2229.0, 805.0, 590.0, -0.1, 0.05};
    geometry::WriteLensCalibration(dir_ / "lens.json", c);
  }
  fs::path dir_;
};

TEST_F(RigLensCalibrationTest, ReferencedCalibrationReplacesTheNominalIntrinsics) {
  const geometry::RigDescription nominal = ReadRigDescription(WriteRig(""));
  EXPECT_TRUE(nominal.lens_calibration.empty());
  EXPECT_EQ(nominal.geometry.intrinsics.k1, 0);
  WriteCalibration(1600, 1200, "Nikon DSC D750");
  const geometry::RigDescription rig =
      ReadRigDescription(WriteRig("calibration: {lens: lens.json}"));
  EXPECT_EQ(rig.lens_calibration, dir_ / "lens.json");
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.fx, 2230.0);
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.cy, 590.0);
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.k1, -0.1);
}

TEST_F(RigLensCalibrationTest, CalibrationOfAnotherCameraIsRefusedAtItsLine) {
  WriteCalibration(6000, 4000, "");
  try {
    ReadRigDescription(WriteRig("calibration: {lens: lens.json}"));
    FAIL() << "expected a refusal";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("another camera"), std::string::npos) << e.what();
  }
  WriteCalibration(1600, 1200, "Canon EOS R5");
  EXPECT_THROW(ReadRigDescription(WriteRig("calibration: {lens: lens.json}")), FileError);
  EXPECT_THROW(ReadRigDescription(WriteRig("calibration: {lens: missing.json}")), FileError);
  EXPECT_THROW(ReadRigDescription(WriteRig("calibration: {lenz: lens.json}")), FileError);
}

}  // namespace
}  // namespace brdfrig::rig
