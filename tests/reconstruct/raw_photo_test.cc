// RAW decoding through LibRaw. No camera maker's file can be committed, so the test writes a
// minimal linear DNG (uncompressed LinearRaw, identity colour matrix, neutral white balance)
// with a known step in it, and checks that the decoded values stay linear and in place.
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

namespace brdfrig::reconstruct {
namespace {

// Little-endian TIFF with one IFD. Values longer than four bytes go after the IFD.
class DngWriter {
 public:
  void Short(uint16_t tag, std::vector<uint16_t> v) {
    std::vector<uint8_t> d;
    for (uint16_t x : v) Append(&d, x, 2);
    entries_.push_back({tag, 3, static_cast<uint32_t>(v.size()), d});
  }
  void Long(uint16_t tag, std::vector<uint32_t> v) {
    std::vector<uint8_t> d;
    for (uint32_t x : v) Append(&d, x, 4);
    entries_.push_back({tag, 4, static_cast<uint32_t>(v.size()), d});
  }
  void Bytes(uint16_t tag, std::vector<uint8_t> v) {
    entries_.push_back({tag, 1, static_cast<uint32_t>(v.size()), v});
  }
  void Ascii(uint16_t tag, const std::string& s) {
    std::vector<uint8_t> d(s.begin(), s.end());
    d.push_back(0);
    entries_.push_back({tag, 2, static_cast<uint32_t>(d.size()), d});
  }
  // type 5 = RATIONAL, 10 = SRATIONAL; each value is numerator/1.
  void Rational(uint16_t tag, uint16_t type, std::vector<int32_t> v) {
    std::vector<uint8_t> d;
    for (int32_t x : v) {
      Append(&d, static_cast<uint32_t>(x), 4);
      Append(&d, 1, 4);
    }
    entries_.push_back({tag, type, static_cast<uint32_t>(v.size()), d});
  }

  // Writes the IFD (entries sorted by tag as TIFF requires) followed by the pixel strip,
  // whose offset goes into StripOffsets (tag 273).
  std::vector<uint8_t> Finish(const std::vector<uint16_t>& pixels) {
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
    const uint32_t ifd = 8;
    const uint32_t after_ifd = ifd + 2 + static_cast<uint32_t>(entries_.size()) * 12 + 4;
    std::vector<uint8_t> blobs;
    std::vector<uint32_t> offsets(entries_.size(), 0);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].data.size() <= 4) continue;
      offsets[i] = after_ifd + static_cast<uint32_t>(blobs.size());
      blobs.insert(blobs.end(), entries_[i].data.begin(), entries_[i].data.end());
      if (blobs.size() % 2) blobs.push_back(0);
    }
    const uint32_t pixel_offset = after_ifd + static_cast<uint32_t>(blobs.size());
    std::vector<uint8_t> out = {'I', 'I'};
    Append(&out, 42, 2);
    Append(&out, ifd, 4);
    Append(&out, entries_.size(), 2);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      Entry& e = entries_[i];
      if (e.tag == 273) {
        e.data.clear();
        Append(&e.data, pixel_offset, 4);
      }
      Append(&out, e.tag, 2);
      Append(&out, e.type, 2);
      Append(&out, e.count, 4);
      if (e.data.size() > 4) {
        Append(&out, offsets[i], 4);
      } else {
        std::vector<uint8_t> inline_value = e.data;
        inline_value.resize(4, 0);
        out.insert(out.end(), inline_value.begin(), inline_value.end());
      }
    }
    Append(&out, 0, 4);  // no next IFD
    out.insert(out.end(), blobs.begin(), blobs.end());
    for (uint16_t p : pixels) Append(&out, p, 2);
    return out;
  }

 private:
  struct Entry {
    uint16_t tag, type;
    uint32_t count;
    std::vector<uint8_t> data;
  };
  static void Append(std::vector<uint8_t>* out, uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out->push_back(static_cast<uint8_t>(value >> (8 * i)));
  }
  std::vector<Entry> entries_;
};

// A W×H linear DNG whose left half holds `left` and right half `right` in every channel.
std::string LinearDng(int width, int height, uint16_t left, uint16_t right) {
  std::vector<uint16_t> pixels;
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) pixels.insert(pixels.end(), 3, x < width / 2 ? left : right);
  }
  const auto w = static_cast<uint32_t>(width), h = static_cast<uint32_t>(height);
  DngWriter dng;
  dng.Long(254, {0});                                    // NewSubFileType: main image
  dng.Long(256, {w});                                    // ImageWidth
  dng.Long(257, {h});                                    // ImageLength
  dng.Short(258, {16, 16, 16});                          // BitsPerSample
  dng.Short(259, {1});                                   // Compression: none
  dng.Short(262, {34892});                               // PhotometricInterpretation: LinearRaw
  dng.Ascii(271, "brdfrig");                             // Make
  dng.Ascii(272, "test");                                // Model
  dng.Long(273, {0});                                    // StripOffsets (filled in by Finish)
  dng.Short(277, {3});                                   // SamplesPerPixel
  dng.Long(278, {h});                                    // RowsPerStrip
  dng.Long(279, {w * h * 6});                            // StripByteCounts
  dng.Short(284, {1});                                   // PlanarConfiguration: chunky
  dng.Bytes(50706, {1, 4, 0, 0});                        // DNGVersion
  dng.Ascii(50708, "brdfrig test");                      // UniqueCameraModel
  dng.Long(50717, {65535});                              // WhiteLevel
  dng.Rational(50721, 10, {1, 0, 0, 0, 1, 0, 0, 0, 1});  // ColorMatrix1: identity
  dng.Rational(50728, 5, {1, 1, 1});                     // AsShotNeutral
  dng.Short(50778, {21});                                // CalibrationIlluminant1: D65
  const std::vector<uint8_t> bytes = dng.Finish(pixels);
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

}  // namespace
}  // namespace brdfrig::reconstruct
