// RAW decoding through LibRaw. No camera maker's file can be committed, so the test writes a
// minimal linear DNG (sim/linear_dng.h: uncompressed LinearRaw, sRGB primaries, neutral
// white balance) with a known step in it, and checks that the decoded values stay
// linear and in place.
#include "reconstruct/raw_photo.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "common/atomic_file.h"
#include "common/error.h"
#include "reconstruct/hdr_merge.h"
#include "sim/linear_dng.h"

namespace brdfrig::reconstruct {
namespace {

// A W×H linear DNG whose left half holds `left` and right half `right` in every channel.
std::string LinearDng(int width, int height, uint16_t left, uint16_t right) {
  cv::Mat bgr(height, width, CV_16UC3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const uint16_t v = x < width / 2 ? left : right;
      bgr.at<cv::Vec<uint16_t, 3>>(y, x) = {v, v, v};
    }
  }
  const std::vector<uint8_t> bytes = sim::EncodeLinearDng(bgr, "test");
  return std::string(bytes.begin(), bytes.end());
}

std::filesystem::path Scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "brdfrig_raw_photo_test";
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(RawPhoto, RecognizesRawExtensions) {
  EXPECT_TRUE(IsRawPhoto("a/IMG_0001.CR2"));
  EXPECT_TRUE(IsRawPhoto("DSC_0042.nef"));
  EXPECT_TRUE(IsRawPhoto("x.dng"));
  EXPECT_FALSE(IsRawPhoto("x.png"));
  EXPECT_FALSE(IsRawPhoto("x.jpg"));
  EXPECT_FALSE(IsRawPhoto("nef"));
}

TEST(RawPhoto, LinearDngDecodesLinearlyWithTheSensorGrid) {
  const auto path = Scratch("linear.dng");
  WriteFileAtomically(path, LinearDng(64, 48, 4000, 8000));
  const cv::Mat image = ReadPhoto(path.string());  // the pipeline's entry point
  ASSERT_EQ(image.type(), CV_16UC3);
  ASSERT_EQ(image.cols, 64);
  ASSERT_EQ(image.rows, 48);
  for (int c = 0; c < 3; ++c) {
    const double left = image.at<cv::Vec3w>(24, 8)[c], right = image.at<cv::Vec3w>(24, 56)[c];
    EXPECT_NEAR(left, 4000, 4000 * 0.01) << "channel " << c;
    EXPECT_NEAR(right / left, 2.0, 0.01) << "channel " << c;  // linear: no gamma, no brightening
  }
}

// LibRaw by default takes a frame's own maximum as its white level when that maximum lies
// above 75 % of the real one, and scales the frame up: a mid exposure of a bracket whose
// brightest pixel reaches 86 % of full scale would come out 16 % too bright.
TEST(RawPhoto, BrightFrameBelowWhiteIsNotRescaledToItsOwnMaximum) {
  const auto path = Scratch("bright.dng");
  WriteFileAtomically(path, LinearDng(64, 48, 28000, 56000));
  const cv::Mat image = ReadPhoto(path.string());
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(image.at<cv::Vec3w>(24, 8)[c], 28000, 28000 * 0.005) << "channel " << c;
    EXPECT_NEAR(image.at<cv::Vec3w>(24, 56)[c], 56000, 56000 * 0.005) << "channel " << c;
  }
}

TEST(RawPhoto, CorruptRawNamesTheFile) {
  const auto path = Scratch("DSC_0001.NEF");
  WriteFileAtomically(path, "this is not a raw file");
  try {
    ReadPhoto(path.string());
    FAIL() << "a corrupt RAW file was decoded";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("DSC_0001.NEF"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("cannot decode RAW"), std::string::npos) << e.what();
  }
}

// fuzz_photo's find: bytes that are no PNG, JPEG or TIFF but hold "DICM" reached OpenCV's DICOM
// decoder (GDCM), which aborted the process. They are refused with the file's name instead.
TEST(RawPhoto, AFileOfAnotherFormatIsRefusedBeforeOpenCvSeesIt) {
  const auto path = Scratch("p00_e0.png");
  std::string bytes = "=PNG\r\n\x1a\n";
  bytes += std::string(120, '\0') + "DICM" + std::string(64, '\x01');
  WriteFileAtomically(path, bytes);
  try {
    ReadPhoto(path.string());
    FAIL() << "a file of another format was decoded";
  } catch (const FileError& e) {
    EXPECT_NE(std::string(e.what()).find("p00_e0.png"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not a PNG, JPEG or TIFF"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace brdfrig::reconstruct
