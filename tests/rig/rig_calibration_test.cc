// rig.yaml's `calibration: {lens, flat, white, light}` and `changed:`: the measured intrinsics,
// paper albedo and light position replace the geometry's, a calibration of another camera or a
// missing file is an error at the line that names it, and `rig calibrate status` tells what is
// nominal and what stale.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "common/error.h"
#include "common/utc_time.h"
#include "geometry/lens_calibration_file.h"
#include "geometry/light_calibration_file.h"
#include "geometry/white_reference_file.h"
#include "rig/calibration_status.h"
#include "rig/rig_file.h"

namespace brdfrig::rig {
namespace {

namespace fs = std::filesystem;

class RigCalibrationTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / "rig_calibration_test";
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  fs::path WriteRig(const std::string& calibration_line, const std::string& more = "") {
    const fs::path rig = dir_ / "rig.yaml";
    std::ofstream(rig) << "geometry: " << BRDFRIG_SOURCE_DIR << "/sim/scenes/default.yaml\n"
                       << "camera: {backend: gphoto2, model: \"Nikon DSC D750\"}\n"
                       << calibration_line << "\n"
                       << more;
    return rig;
  }
  void WriteCalibration(int width, int height, const std::string& model) {
    geometry::LensCalibration c;
    c.created = "2026-12-02T10:00:00Z";
    c.camera_model = model;
    c.intrinsics = {width, height, 2230.0, 2229.0, 805.0, 590.0, -0.1, 0.05};
    geometry::WriteLensCalibration(dir_ / "lens.json", c);
  }
  void WriteWhite(double paper_albedo, const std::string& created = "2026-12-02T11:00:00Z") {
    geometry::WhiteReference r;
    r.created = created;
    r.paper_albedo = paper_albedo;
    r.reference_albedo = 0.5;
    r.tile_spread = 0.004;
    geometry::WriteWhiteReference(dir_ / "white.json", r);
  }
  void WriteLight(const geometry::Vec3& position, const std::string& created) {
    geometry::LightCalibration c;
    c.created = created;
    c.light_position = position;
    c.nominal_offset_m = 0.005;
    c.rms_miss_m = 0.00002;
    c.dilution = 11;
    c.photos.resize(5);
    geometry::WriteLightCalibration(dir_ / "light.json", c);
  }
  fs::path dir_;
};

TEST_F(RigCalibrationTest, ReferencedCalibrationReplacesTheNominalIntrinsics) {
  const geometry::RigDescription nominal = ReadRigDescription(WriteRig(""));
  EXPECT_TRUE(nominal.calibration.Empty());
  EXPECT_EQ(nominal.geometry.intrinsics.k1, 0);
  WriteCalibration(1600, 1200, "Nikon DSC D750");
  const geometry::RigDescription rig =
      ReadRigDescription(WriteRig("calibration: {lens: lens.json}"));
  EXPECT_EQ(rig.calibration.lens, dir_ / "lens.json");
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.fx, 2230.0);
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.cy, 590.0);
  EXPECT_DOUBLE_EQ(rig.geometry.intrinsics.k1, -0.1);
}

TEST_F(RigCalibrationTest, CalibrationOfAnotherCameraIsRefusedAtItsLine) {
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

TEST_F(RigCalibrationTest, WhiteReferenceReplacesThePaperAlbedoAndTheFlatFieldIsRecorded) {
  WriteWhite(0.7512);
  std::ofstream(dir_ / "flat.exr") << "a gain map";  // read by the reconstruction, not here
  const geometry::RigDescription rig =
      ReadRigDescription(WriteRig("calibration: {white: white.json, flat: flat.exr}"));
  EXPECT_DOUBLE_EQ(rig.geometry.target.paper_albedo, 0.7512);
  EXPECT_EQ(rig.calibration.white, dir_ / "white.json");
  EXPECT_EQ(rig.calibration.flat, dir_ / "flat.exr");
  EXPECT_TRUE(rig.calibration.lens.empty());
  EXPECT_EQ(rig.calibration.NominalOnes(), "lens, light");
  const nlohmann::json provenance = rig.calibration.Provenance();
  EXPECT_EQ(provenance["lens"], "nominal");
  EXPECT_EQ(provenance["white"]["file"], "white.json");
  EXPECT_EQ(provenance["flat"]["sha256"].get<std::string>().size(), 64u);
}

TEST_F(RigCalibrationTest, LightCalibrationReplacesTheNominalLightPosition) {
  const geometry::Vec3 measured(0.003, 0.004, 0.6001);
  WriteLight(measured, "2026-12-03T09:00:00Z");
  const geometry::RigDescription rig =
      ReadRigDescription(WriteRig("calibration: {light: light.json}"));
  EXPECT_EQ(rig.geometry.light_position, measured);
  EXPECT_EQ(rig.calibration.light, dir_ / "light.json");
  EXPECT_EQ(rig.calibration.Provenance()["light"]["file"], "light.json");
  WriteLight({0.003, 0.004, -0.6}, "2026-12-03T09:00:00Z");  // below the sample: not a light
  try {
    ReadRigDescription(WriteRig("calibration: {light: light.json}"));
    FAIL() << "expected a refusal";
  } catch (const FileError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(std::string(e.what()).find("above the sample plane"), std::string::npos) << e.what();
  }
}

TEST_F(RigCalibrationTest, MissingOrMalformedCalibrationsAndBadDatesAreErrorsAtTheirLine) {
  for (const char* line : {"calibration: {flat: missing.exr}", "calibration: {white: no.json}"}) {
    try {
      ReadRigDescription(WriteRig(line));
      FAIL() << "expected a refusal of " << line;
    } catch (const FileError& e) {
      EXPECT_EQ(e.line(), 3) << e.what();
      EXPECT_NE(std::string(e.what()).find("not found"), std::string::npos) << e.what();
    }
  }
  WriteWhite(1.4);  // an albedo above 1
  EXPECT_THROW(ReadRigDescription(WriteRig("calibration: {white: white.json}")), FileError);
  for (const char* date : {"2026-02-30", "yesterday", "2026-12-02T10:00:00+01:00"}) {
    try {
      ReadRigDescription(WriteRig("", std::string("changed: ") + date + "\n"));
      FAIL() << "expected a refusal of " << date;
    } catch (const FileError& e) {
      EXPECT_EQ(e.line(), 4) << e.what();
    }
  }
  EXPECT_EQ(ReadRigDescription(WriteRig("", "changed: 2026-11-30\n")).changed, "2026-11-30");
}

TEST(UtcTimeTest, DatesAndUtcTimesParseAndOthersDoNot) {
  EXPECT_EQ(ParseUtcIso8601("1970-01-02"), std::optional<std::time_t>(86400));
  EXPECT_EQ(ParseUtcIso8601("1970-01-01T01:00:01Z"), std::optional<std::time_t>(3601));
  for (const char* bad : {"", "2026-13-01", "2026-02-29", "2026-12-02T24:00:00Z",
                          "2026-12-02 10:00:00Z", "2026-12-02T10:00:00", "2026-12-02x"}) {
    EXPECT_FALSE(ParseUtcIso8601(bad).has_value()) << bad;
  }
  EXPECT_TRUE(ParseUtcIso8601(NowUtcIso8601()).has_value());
}

TEST_F(RigCalibrationTest, StatusNamesNominalAndStaleCalibrations) {
  // Nothing calibrated: every value nominal, not current.
  CalibrationStatus status = ReadCalibrationStatus(WriteRig(""));
  EXPECT_FALSE(status.Current());
  EXPECT_NE(status.ToString().find("NOMINAL"), std::string::npos) << status.ToString();
  EXPECT_NE(status.ToString().find("not said"), std::string::npos) << status.ToString();

  WriteCalibration(1600, 1200, "Nikon DSC D750");  // made 2026-12-02T10:00:00Z
  WriteWhite(0.75);                                // made 2026-12-02T11:00:00Z
  std::ofstream(dir_ / "flat.exr") << "a gain map";
  std::ofstream(dir_ / "flat.exr.json") << R"({"created": "2026-12-02T12:00:00Z",
                                              "fit_rms": 0.004, "min_gain": 0.8, "max_gain": 1.1})";
  WriteLight({0.003, 0.004, 0.6}, "2026-12-02T13:00:00Z");
  const std::string all =
      "calibration: {lens: lens.json, flat: flat.exr, white: white.json, light: light.json}";
  status = ReadCalibrationStatus(WriteRig(all, "changed: 2026-12-01\n"));
  EXPECT_TRUE(status.Current()) << status.ToString();
  ASSERT_EQ(status.calibrations.size(), 4u);
  EXPECT_NE(status.calibrations[3].figure.find("RMS miss 0.02 mm over 5 photos, 5.0 mm from"),
            std::string::npos)
      << status.calibrations[3].figure;
  EXPECT_EQ(status.calibrations[1].created, "2026-12-02T12:00:00Z");
  EXPECT_NE(status.calibrations[1].figure.find("fit RMS 0.40 %"), std::string::npos)
      << status.calibrations[1].figure;
  EXPECT_NE(status.calibrations[2].figure.find("paper albedo 0.7500"), std::string::npos);

  // The lamp was moved at 10:30: the lens (10:00) is stale, the rest was made after.
  status = ReadCalibrationStatus(WriteRig(all, "changed: 2026-12-02T10:30:00Z\n"));
  EXPECT_FALSE(status.Current());
  EXPECT_TRUE(status.calibrations[0].stale);
  EXPECT_FALSE(status.calibrations[1].stale);
  EXPECT_FALSE(status.calibrations[2].stale);
  EXPECT_FALSE(status.calibrations[3].stale);
  EXPECT_NE(status.ToString().find("STALE"), std::string::npos) << status.ToString();

  // A gain map without its record is of unknown age: stale once the rig says when it changed.
  fs::remove(dir_ / "flat.exr.json");
  status = ReadCalibrationStatus(WriteRig(all, "changed: 2026-12-01\n"));
  EXPECT_TRUE(status.calibrations[1].stale);
  EXPECT_NE(status.calibrations[1].figure.find("no record"), std::string::npos);
}

}  // namespace
}  // namespace brdfrig::rig
