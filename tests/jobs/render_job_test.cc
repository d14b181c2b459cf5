#include "jobs/render_job.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"
#include "sim/image_io.h"

namespace brdfrig::jobs {
namespace {

namespace fs = std::filesystem;
const fs::path kSource = BRDFRIG_SOURCE_DIR;

TEST(RenderJobTest, RendersASceneCapturePositionToExr) {
  RenderJobOptions options;
  options.material = kSource / "tests/data/glossy_slices.json";
  options.scene = kSource / "sim/scenes/default.yaml";
  options.position = 1;
  options.output = fs::temp_directory_path() / "brdfrig_render_job.exr";
  const RenderJobSummary s = RunRenderJob(options);
  EXPECT_EQ(s.width, 1600);
  const cv::Mat radiance = sim::ReadRadianceExr(options.output);
  ASSERT_EQ(radiance.cols, 1600);
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
  RunRenderJob(options);
  EXPECT_GT(fs::file_size(options.output), 100u);
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
  options.scene = kSource / "sim/scenes/default.yaml";
  options.position = 99;
  options.output = fs::temp_directory_path() / "x.png";
  EXPECT_THAT([&] { RunRenderJob(options); },
              ::testing::ThrowsMessage<OptionsError>(::testing::HasSubstr("6 capture positions")));
}

}  // namespace
}  // namespace brdfrig::jobs
