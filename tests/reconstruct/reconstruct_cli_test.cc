// `brdfrig reconstruct` never degrades silently (issue 15, finding 5): a session frame changed
// since capture is dropped with its reason in material.json and exit status 3, refused under
// --strict (exit 1, nothing written); NaN/Inf pixels are masked and the position reported as
// degraded (exit status 3 as well); grey photos and negative position indices are errors.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/exr_io.h"
#include "reconstruct/hdr_merge.h"
#include "tests/common/run_brdfrig.h"
#include "tests/reconstruct/capture_fixture.h"

namespace brdfrig::reconstruct {
namespace {

namespace fs = std::filesystem;

using brdfrig::testing::RunBrdfrig;

std::string Q(const fs::path& p) { return "'" + p.string() + "'"; }

testing::SceneSpec SmallScene() {
  testing::SceneSpec spec;
  spec.width = 320;
  spec.height = 240;
  spec.supersampling = 4;
  return spec;
}

nlohmann::json ReadJson(const fs::path& file) {
  return nlohmann::json::parse(ReadFileToString(file));
}

TEST(ReconstructCli, ChangedFrameIsDroppedWithExitThreeAndRefusedUnderStrict) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_reconstruct_cli_hash";
  fs::remove_all(dir);
  fs::create_directories(dir);
  brdf::WriteMaterialFile(dir / "truth.json", testing::FlatSliceTruth());
  std::ofstream(dir / "scene.yaml") << testing::SceneYaml(SmallScene());
  std::ofstream(dir / "rig.yaml") << "geometry: scene.yaml\n"
                                     "camera: {backend: sim, scene: scene.yaml}\n"
                                     "axes:\n"
                                     "  camera_arm: {backend: sim, scene: scene.yaml}\n"
                                     "  light_arm: {backend: sim, scene: scene.yaml}\n";
  std::ofstream(dir / "plan.yaml") << "sample: flat-slices\n"
                                      "positions:\n"
                                      "  - {camera_arm: 20, light_arm: -20}\n"
                                      "  - {camera_arm: 35, light_arm: -35}\n"
                                      "  - {camera_arm: 50, light_arm: -50}\n"
                                      "exposures: [0.001, 0.008, 0.0666667]\n"
                                      "settle_s: 0\n";
  const fs::path session = dir / "session";
  const auto captured = RunBrdfrig("capture --rig " + Q(dir / "rig.yaml") + " --plan " +
                                   Q(dir / "plan.yaml") + " -o " + Q(session));
  ASSERT_EQ(captured.status, 0) << captured.output;

  const auto complete =
      RunBrdfrig("reconstruct --model seed " + Q(session) + " -o " + Q(dir / "a/material.json"));
  EXPECT_EQ(complete.status, 0) << complete.output;
  EXPECT_EQ(ReadJson(dir / "a/material.json")["provenance"]["dropped_positions"], 0);

  // Still a valid PNG (bytes after IEND are ignored by decoders), but not the recorded frame.
  std::ofstream(session / "frames" / "p001_b1.png", std::ios::app) << "tampered";
  const auto partial =
      RunBrdfrig("reconstruct --model seed " + Q(session) + " -o " + Q(dir / "b/material.json"));
  EXPECT_EQ(partial.status, 3) << partial.output;
  EXPECT_NE(partial.output.find("partial"), std::string::npos) << partial.output;
  EXPECT_NE(partial.output.find("dropped p01"), std::string::npos) << partial.output;
  const nlohmann::json provenance = ReadJson(dir / "b/material.json")["provenance"];
  EXPECT_EQ(provenance["dropped_positions"], 1);
  const nlohmann::json& p1 = provenance["positions"][1];
  EXPECT_EQ(p1["index"], 1);
  EXPECT_EQ(p1["used"], false);
  EXPECT_NE(p1["skipped"].get<std::string>().find("p001_b1.png"), std::string::npos) << p1;
  EXPECT_NE(p1["skipped"].get<std::string>().find("SHA-256"), std::string::npos) << p1;
  EXPECT_EQ(ReadJson(dir / "b/material.json")["slices"].size(), 2u);

  // Up to date but partial: still exit 3, not a silent 0.
  const auto again =
      RunBrdfrig("reconstruct --model seed " + Q(session) + " -o " + Q(dir / "b/material.json"));
  EXPECT_EQ(again.status, 3) << again.output;

  const auto strict = RunBrdfrig("reconstruct --strict --model seed " + Q(session) + " -o " +
                                 Q(dir / "c/material.json"));
  EXPECT_EQ(strict.status, 1) << strict.output;
  EXPECT_NE(strict.output.find("--strict"), std::string::npos) << strict.output;
  EXPECT_FALSE(fs::exists(dir / "c/material.json"));

  // A batch over a directory of sessions reports each one's status.
  fs::create_directories(dir / "sessions");
  fs::rename(session, dir / "sessions" / "tampered");
  const auto batch =
      RunBrdfrig("reconstruct --model seed " + Q(dir / "sessions") + " -o " + Q(dir / "fits"));
  EXPECT_EQ(batch.status, 3) << batch.output;
  EXPECT_NE(batch.output.find("partial"), std::string::npos) << batch.output;
}

TEST(ReconstructCli, NegativePositionIndexNamesTheFile) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_reconstruct_cli_negative";
  fs::remove_all(dir);
  fs::create_directories(dir / "photos");
  std::ofstream(dir / "photos" / "scene.yaml") << testing::SceneYaml(SmallScene());
  std::ofstream(dir / "photos" / "capture.json")
      << R"({"scene": "scene.yaml", "frames": [{"position_index": -1, "file": "a.png",
            "exposure_s": 0.01, "axis_readings_rad": {}}]})";
  const auto result = RunBrdfrig("reconstruct " + Q(dir) + " -o " + Q(dir / "out.json"));
  EXPECT_EQ(result.status, 1) << result.output;
  EXPECT_NE(result.output.find("capture.json"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("position_index -1 is negative"), std::string::npos)
      << result.output;
}

TEST(ReconstructCli, GreyPhotoIsAnErrorNotColour) {
  const fs::path file = fs::temp_directory_path() / "brdfrig_reconstruct_cli_grey.png";
  cv::imwrite(file.string(), cv::Mat(8, 8, CV_8UC1, cv::Scalar(128)));
  try {
    ReadPhoto(file.string());
    FAIL() << "a grey photo was read as colour";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("grey"), std::string::npos) << e.what();
  }
}

TEST(ReconstructCli, NonFinitePixelsAreInvalidAndReported) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_reconstruct_cli_nan";
  const brdf::Material truth = testing::FlatSliceTruth();
  CaptureSet capture = testing::SimulateCapture(dir, SmallScene(), &truth);
  // Position 0's photos as linear float EXR (what a converted RAW might be), with a block of
  // NaN and Inf at the centre of the cut-out in the longest exposure.
  for (BracketFrame& frame : capture.positions[0].frames) {
    cv::Mat image = cv::imread(frame.file.string(), cv::IMREAD_UNCHANGED);
    image.convertTo(image, CV_32FC3, 1.0 / 65535);
    if (frame.exposure_s > 0.05) {
      image(cv::Rect(150, 110, 10, 10)).setTo(cv::Scalar::all(NAN));
      image(cv::Rect(160, 110, 5, 5)).setTo(cv::Scalar::all(INFINITY));
    }
    frame.file.replace_extension(".exr");
    WriteRadianceExr(frame.file, image);
  }
  const ReconstructionResult result = Reconstruct(capture, testing::SeedOnly());
  const nlohmann::json p0 = result.material.provenance["positions"][0];
  EXPECT_EQ(p0["used"], true) << p0;
  EXPECT_EQ(p0.value("non_finite_pixels", 0), 125) << p0;
  ASSERT_TRUE(p0.contains("warnings")) << p0;
  EXPECT_NE(p0["warnings"].dump().find("NaN or infinite"), std::string::npos) << p0;
  // Used, but degraded: recorded as such, like a dropped position.
  ASSERT_EQ(result.Degraded().size(), 1u);
  EXPECT_NE(result.Degraded()[0].find("p00: 125 NaN or infinite"), std::string::npos)
      << result.Degraded()[0];
  EXPECT_NE(p0.value("degraded", "").find("125 NaN or infinite"), std::string::npos) << p0;
  EXPECT_EQ(result.material.provenance["degraded_positions"], 1);

  // Through the executable: the manifest names the EXR files; exit status 3, the position
  // listed as degraded, and a failure under --strict.
  const fs::path photos = capture.positions[0].frames[0].file.parent_path();
  nlohmann::json manifest = ReadJson(photos / "capture.json");
  for (auto& frame : manifest["frames"]) {
    if (frame["position_index"] == 0) {
      frame["file"] = fs::path(frame["file"].get<std::string>()).replace_extension(".exr").string();
    }
  }
  WriteFileAtomically(photos / "capture.json", manifest.dump());
  const fs::path out = dir / "fit" / "material.json";
  const auto partial = RunBrdfrig("reconstruct --model seed " + Q(photos) + " -o " + Q(out));
  EXPECT_EQ(partial.status, 3) << partial.output;
  EXPECT_NE(partial.output.find("degraded p00"), std::string::npos) << partial.output;
  EXPECT_EQ(ReadJson(out)["provenance"]["degraded_positions"], 1);
  const fs::path strict_out = dir / "strict" / "material.json";
  const auto strict =
      RunBrdfrig("reconstruct --strict --model seed " + Q(photos) + " -o " + Q(strict_out));
  EXPECT_EQ(strict.status, 1) << strict.output;
  EXPECT_NE(strict.output.find("degraded"), std::string::npos) << strict.output;
  EXPECT_FALSE(fs::exists(strict_out));
}

// Issue 25, finding 8: the options that change the material are part of the up-to-date key, so
// a second run with another --model (or another fit option) refits; the same options skip.
TEST(ReconstructCli, ChangedModelOrFitOptionRefitsInsteadOfUpToDate) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_reconstruct_cli_options";
  const brdf::Material truth = testing::FlatSliceTruth();
  const CaptureSet capture = testing::SimulateCapture(dir, SmallScene(), &truth);
  const fs::path photos = capture.positions[0].frames[0].file.parent_path();
  const fs::path out = dir / "fit" / "material.json";
  const std::string reconstruct = "reconstruct " + Q(photos) + " -o " + Q(out);
  const auto ggx = RunBrdfrig(reconstruct + " --model ggx");
  ASSERT_EQ(ggx.status, 0) << ggx.output;
  EXPECT_EQ(ReadJson(out)["kind"], "ggx");
  const auto beckmann = RunBrdfrig(reconstruct + " --model beckmann");
  ASSERT_EQ(beckmann.status, 0) << beckmann.output;
  EXPECT_EQ(beckmann.output.find("up to date"), std::string::npos) << beckmann.output;
  EXPECT_EQ(ReadJson(out)["kind"], "beckmann");
  const auto again = RunBrdfrig(reconstruct + " --model beckmann");
  EXPECT_NE(again.output.find("up to date"), std::string::npos) << again.output;
  const auto binned = RunBrdfrig(reconstruct + " --model beckmann --bin-width-deg 0.05");
  ASSERT_EQ(binned.status, 0) << binned.output;
  EXPECT_EQ(binned.output.find("up to date"), std::string::npos) << binned.output;
  EXPECT_EQ(ReadJson(out)["provenance"]["options"]["model"], "beckmann");
}

// Issue 25, finding 7: a relative scene in capture.json is the one beside it; a scene.yaml in
// the directory the command runs from is never read (here one that is not even YAML).
TEST(ReconstructCli, RelativeSceneIsReadBesideTheCaptureNotTheCurrentDirectory) {
  const fs::path dir = fs::temp_directory_path() / "brdfrig_reconstruct_cli_relative_scene";
  const brdf::Material truth = testing::FlatSliceTruth();
  const CaptureSet capture = testing::SimulateCapture(dir, SmallScene(), &truth);
  const fs::path photos = capture.positions[0].frames[0].file.parent_path();
  nlohmann::json manifest = ReadJson(photos / "capture.json");
  EXPECT_TRUE(fs::path(manifest["scene"].get<std::string>()).is_absolute()) << manifest["scene"];
  manifest["scene"] = "scene.yaml";
  WriteFileAtomically(photos / "capture.json", manifest.dump());
  fs::copy_file(dir / "scene.yaml", photos / "scene.yaml");
  const fs::path elsewhere = dir / "elsewhere";
  fs::create_directories(elsewhere);
  std::ofstream(elsewhere / "scene.yaml") << "rig: [this is not the capture's scene\n";
  const fs::path before = fs::current_path();
  fs::current_path(elsewhere);
  const auto result = RunBrdfrig("reconstruct --model seed " + Q(photos) + " -o " +
                                 Q(dir / "fit" / "material.json"));
  fs::current_path(before);
  EXPECT_EQ(result.status, 0) << result.output;
  EXPECT_EQ(result.output.find("elsewhere"), std::string::npos) << result.output;
}

}  // namespace
}  // namespace brdfrig::reconstruct
