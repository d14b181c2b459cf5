// common/exr_io.h: float RGB round trip, and the size bound (a header of a few hundred bytes
// claiming 1.6 gigapixels made the reader allocate 19 GB).
#include "common/exr_io.h"

#include <ImfChannelList.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "common/error.h"

namespace brdfrig {
namespace {

namespace fs = std::filesystem;

TEST(ExrIo, RoundTripKeepsFloatBgr) {
  const fs::path file = fs::temp_directory_path() / "brdfrig_exr_roundtrip.exr";
  cv::Mat image(3, 4, CV_32FC3);
  cv::randu(image, 0.0f, 4.0f);
  WriteRadianceExr(file, image);
  const cv::Mat back = ReadRadianceExr(file);
  ASSERT_EQ(back.type(), CV_32FC3);
  ASSERT_EQ(back.size(), image.size());
  EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0);
}

TEST(ExrIo, DataWindowBeyondTheBoundsIsAFileErrorBeforeAnyAllocation) {
  const fs::path file = fs::temp_directory_path() / "brdfrig_exr_huge.exr";
  {
    // Only the header and the line offsets are written: 40000 x 40000 pixels claimed.
    const Imath::Box2i window(Imath::V2i(0, 0), Imath::V2i(39999, 39999));
    Imf::Header header(window, window);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::OutputFile out(file.c_str(), header);
  }
  EXPECT_THAT([&] { ReadRadianceExr(file); },
              ::testing::ThrowsMessage<FileError>(
                  ::testing::AllOf(::testing::HasSubstr("brdfrig_exr_huge.exr"),
                                   ::testing::HasSubstr("data window of 40000x40000"))));
}

}  // namespace
}  // namespace brdfrig
