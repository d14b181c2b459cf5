#include "sim/linear_dng.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"

namespace brdfrig::sim {
namespace {

// Little-endian TIFF with one IFD; values longer than four bytes go after the IFD, the pixel
// strip after them.
class TiffWriter {
 public:
  void Short(std::uint16_t tag, const std::vector<std::uint16_t>& v) {
    Entry e{tag, 3, static_cast<std::uint32_t>(v.size()), {}};
    for (std::uint16_t x : v) Append(&e.data, x, 2);
    entries_.push_back(std::move(e));
  }
  void Long(std::uint16_t tag, const std::vector<std::uint32_t>& v) {
    Entry e{tag, 4, static_cast<std::uint32_t>(v.size()), {}};
    for (std::uint32_t x : v) Append(&e.data, x, 4);
    entries_.push_back(std::move(e));
  }
  void Bytes(std::uint16_t tag, const std::vector<std::uint8_t>& v) {
    entries_.push_back({tag, 1, static_cast<std::uint32_t>(v.size()), v});
  }
  void Ascii(std::uint16_t tag, const std::string& s) {
    std::vector<std::uint8_t> d(s.begin(), s.end());
    d.push_back(0);
    entries_.push_back({tag, 2, static_cast<std::uint32_t>(d.size()), d});
  }
  // type 5 = RATIONAL, 10 = SRATIONAL; each value is written as round(v × 10000)/10000.
  void Rational(std::uint16_t tag, std::uint16_t type, const std::vector<double>& v) {
    Entry e{tag, type, static_cast<std::uint32_t>(v.size()), {}};
    for (double x : v) {
      Append(&e.data, static_cast<std::uint32_t>(static_cast<std::int32_t>(std::lround(x * 1e4))),
             4);
      Append(&e.data, 10000, 4);
    }
    entries_.push_back(std::move(e));
  }

  // The IFD (entries sorted by tag, as TIFF requires), the long values, then the strip, whose
  // offset goes into StripOffsets (273).
  std::vector<std::uint8_t> Finish(const std::vector<std::uint8_t>& strip) {
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& a, const Entry& b) { return a.tag < b.tag; });
    const std::uint32_t ifd = 8;
    const std::uint32_t after_ifd = ifd + 2 + static_cast<std::uint32_t>(entries_.size()) * 12 + 4;
    std::vector<std::uint8_t> blobs;
    std::vector<std::uint32_t> offsets(entries_.size(), 0);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      if (entries_[i].data.size() <= 4) continue;
      offsets[i] = after_ifd + static_cast<std::uint32_t>(blobs.size());
      blobs.insert(blobs.end(), entries_[i].data.begin(), entries_[i].data.end());
      if (blobs.size() % 2) blobs.push_back(0);
    }
    const std::uint32_t strip_offset = after_ifd + static_cast<std::uint32_t>(blobs.size());
    std::vector<std::uint8_t> out = {'I', 'I'};
    Append(&out, 42, 2);
    Append(&out, ifd, 4);
    Append(&out, entries_.size(), 2);
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      Entry& e = entries_[i];
      if (e.tag == 273) {
        e.data.clear();
        Append(&e.data, strip_offset, 4);
      }
      Append(&out, e.tag, 2);
      Append(&out, e.type, 2);
      Append(&out, e.count, 4);
      if (e.data.size() > 4) {
        Append(&out, offsets[i], 4);
      } else {
        std::vector<std::uint8_t> inline_value = e.data;
        inline_value.resize(4, 0);
        out.insert(out.end(), inline_value.begin(), inline_value.end());
      }
    }
    Append(&out, 0, 4);  // no next IFD
    out.insert(out.end(), blobs.begin(), blobs.end());
    out.insert(out.end(), strip.begin(), strip.end());
    return out;
  }

 private:
  struct Entry {
    std::uint16_t tag, type;
    std::uint32_t count;
    std::vector<std::uint8_t> data;
  };
  static void Append(std::vector<std::uint8_t>* out, std::uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out->push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
  std::vector<Entry> entries_;
};

}  // namespace

std::vector<std::uint8_t> EncodeLinearDng(const cv::Mat& bgr16, const std::string& model) {
  if (bgr16.type() != CV_16UC3 || bgr16.empty()) {
    throw Error("EncodeLinearDng: expected a non-empty CV_16UC3 image");
  }
  const auto w = static_cast<std::uint32_t>(bgr16.cols);
  const auto h = static_cast<std::uint32_t>(bgr16.rows);
  std::vector<std::uint8_t> strip;
  strip.reserve(static_cast<std::size_t>(w) * h * 6);
  for (int y = 0; y < bgr16.rows; ++y) {
    const std::uint16_t* row = bgr16.ptr<std::uint16_t>(y);
    for (int x = 0; x < bgr16.cols; ++x) {
      for (int c : {2, 1, 0}) {  // DNG stores R, G, B
        const std::uint16_t v = row[3 * x + c];
        strip.push_back(static_cast<std::uint8_t>(v & 0xFF));
        strip.push_back(static_cast<std::uint8_t>(v >> 8));
      }
    }
  }
  TiffWriter dng;
  dng.Long(254, {0});                    // NewSubFileType: main image
  dng.Long(256, {w});                    // ImageWidth
  dng.Long(257, {h});                    // ImageLength
  dng.Short(258, {16, 16, 16});          // BitsPerSample
  dng.Short(259, {1});                   // Compression: none
  dng.Short(262, {34892});               // PhotometricInterpretation: LinearRaw
  dng.Ascii(271, "brdfrig");             // Make
  dng.Ascii(272, model);                 // Model
  dng.Long(273, {0});                    // StripOffsets (filled in by Finish)
  dng.Short(277, {3});                   // SamplesPerPixel
  dng.Long(278, {h});                    // RowsPerStrip
  dng.Long(279, {w * h * 6});            // StripByteCounts
  dng.Short(284, {1});                   // PlanarConfiguration: chunky
  dng.Bytes(50706, {1, 4, 0, 0});        // DNGVersion
  dng.Ascii(50708, "brdfrig " + model);  // UniqueCameraModel
  dng.Long(50717, {65535});              // WhiteLevel
  // ColorMatrix1 (XYZ → camera) is XYZ → linear sRGB (D65): the camera's primaries are sRGB's,
  // so a raw converter's camera → sRGB step is the identity and every channel decodes to the
  // value written (an identity matrix here would mix the channels on the way out).
  dng.Rational(50721, 10,
               {3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570});
  dng.Rational(50728, 5, {1, 1, 1});  // AsShotNeutral
  dng.Short(50778, {21});             // CalibrationIlluminant1: D65
  return dng.Finish(strip);
}

}  // namespace brdfrig::sim
