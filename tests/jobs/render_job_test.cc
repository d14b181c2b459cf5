#include "jobs/render_job.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "common/error.h"
#include "sim/image_io.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BRDFRIG_SOURCE_DIR;

TEST(RenderJobTest, RendersASceneCapturePositionToExr) {
  RenderJobOptions options;
  options.material = kSource / "tests/data/glossy_slices.json";
  options.scene = kSource / "sim/scenes/ggx.yaml";
  options.position = 1;
  options.output = fs::temp_directory_path() / "brdfrig_render_job.exr";
  const RenderJobSummary s = RunRenderJob(options);
  EXPECT_EQ(s.width, 1600);
  EXPECT_EQ(s.height, 1200);
  const cv::Mat radiance = sim::ReadRadianceExr(options.output);
  ASSERT_EQ(radiance.cols, 1600);
  ASSERT_EQ(radiance.rows, 1200);
  double lo, hi;
  cv::minMaxLoc(radiance.reshape(1), &lo, &hi);
  EXPECT_GE(lo, 0);
  EXPECT_GT(hi, 0);
  fs::remove(options.output);
}

TEST(RenderJobTest, RendersAMeshToPng) {
  RenderJobOptions options;
  options.material = kSource / "tests/data/glossy_slices.json";
  options.mesh = "sphere";
  options.width = 160;
  options.height = 90;
  options.output = fs::temp_directory_path() / "brdfrig_render_job.png";
  const RenderJobSummary s = RunRenderJob(options);
  EXPECT_EQ(s.width, 160);
  EXPECT_EQ(s.height, 90);
  const cv::Mat picture = cv::imread(options.output.string(), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(picture.cols, 160);
  ASSERT_EQ(picture.rows, 90);
  ASSERT_EQ(picture.channels(), 3);
  // The sphere fills the middle of the frame, the background the corner.
  const cv::Vec3b centre = picture.at<cv::Vec3b>(45, 80), corner = picture.at<cv::Vec3b>(0, 0);
  EXPECT_NE(centre, corner);
  EXPECT_GT(cv::norm(centre), 0);
  fs::remove(options.output);
}

TEST(RenderJobTest, BadInputsGiveClearErrors) {
  RenderJobOptions options;
  options.material = kSource / "tests/data/glossy_slices.json";
  options.output = fs::temp_directory_path() / "x.bmp";
  options.width = 16;
  options.height = 16;
  EXPECT_THAT([&] { RunRenderJob(options); },
              ::testing::ThrowsMessage<Error>(::testing::HasSubstr("use .exr")));
  options.material = "/nonexistent/material.json";
  EXPECT_THROW(RunRenderJob(options), FileError);
  options.material = kSource / "tests/data/glossy_slices.json";
  options.scene = kSource / "sim/scenes/ggx.yaml";
  options.position = 99;
  options.output = fs::temp_directory_path() / "x.png";
  EXPECT_THAT([&] { RunRenderJob(options); },
              ::testing::ThrowsMessage<OptionsError>(::testing::HasSubstr("6 capture positions")));
}

}  // namespace
}  // namespace brdfrig::jobs
