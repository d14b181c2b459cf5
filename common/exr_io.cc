#include "common/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include <cstdint>
#include <string>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig {
namespace {

// The largest EXR image read: the camera resolution bound of rig and plan files per side, and
// 2^27 pixels (1.5 GiB as float RGB) in all.
constexpr std::int64_t kMaxExrSide = 32768;
constexpr std::int64_t kMaxExrPixels = std::int64_t{1} << 27;

void InsertChannels(Imf::FrameBuffer* fb, char* base, std::size_t row_bytes) {
  const std::size_t px = 3 * sizeof(float);
  // OpenCV stores B, G, R: R is the third float of a pixel.
  fb->insert("R", Imf::Slice(Imf::FLOAT, base + 2 * sizeof(float), px, row_bytes));
  fb->insert("G", Imf::Slice(Imf::FLOAT, base + 1 * sizeof(float), px, row_bytes));
  fb->insert("B", Imf::Slice(Imf::FLOAT, base, px, row_bytes));
}

}  // namespace

void WriteRadianceExr(const std::filesystem::path& path, const cv::Mat& radiance) {
  CV_Assert(radiance.type() == CV_32FC3 && radiance.isContinuous());
  Imf::Header header(radiance.cols, radiance.rows);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* name : {"R", "G", "B"}) header.channels().insert(name, Imf::Channel(Imf::FLOAT));
  Imf::StdOSStream stream;
  try {
    Imf::OutputFile file(stream, header);
    Imf::FrameBuffer fb;
    InsertChannels(&fb, const_cast<char*>(reinterpret_cast<const char*>(radiance.data)),
                   radiance.step[0]);
    file.setFrameBuffer(fb);
    file.writePixels(radiance.rows);
  } catch (const std::exception& e) {
    throw Error(path.string() + ": cannot encode EXR: " + e.what());
  }
  WriteFileAtomically(path, stream.str());
}

cv::Mat ReadRadianceExr(const std::filesystem::path& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    // In 64 bits: the corners are any ints a file claims, and their difference may not fit.
    const std::int64_t width = std::int64_t{window.max.x} - window.min.x + 1;
    const std::int64_t height = std::int64_t{window.max.y} - window.min.y + 1;
    // A header of a few hundred bytes can claim gigapixels: refused before anything is
    // allocated (issue 15, finding 2: every size read from a file has a bound).
    if (width < 1 || height < 1 || width > kMaxExrSide || height > kMaxExrSide ||
        width * height > kMaxExrPixels) {
      throw FileError(path.string(), "EXR data window of " + std::to_string(width) + "x" +
                                         std::to_string(height) + " pixels: at most " +
                                         std::to_string(kMaxExrSide) + " per side and " +
                                         std::to_string(kMaxExrPixels) + " pixels are read");
    }
    cv::Mat image(static_cast<int>(height), static_cast<int>(width), CV_32FC3, cv::Scalar::all(0));
    char* origin = reinterpret_cast<char*>(image.data) -
                   (static_cast<std::ptrdiff_t>(window.min.y) * image.step[0]) -
                   static_cast<std::ptrdiff_t>(window.min.x) * 3 * sizeof(float);
    Imf::FrameBuffer fb;
    InsertChannels(&fb, origin, image.step[0]);
    file.setFrameBuffer(fb);
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw FileError(path.string(), std::string("cannot read EXR: ") + e.what());
  }
}

}  // namespace brdfrig
