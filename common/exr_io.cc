#include "common/exr_io.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStdIO.h>

#include "common/atomic_file.h"
#include "common/error.h"

namespace brdfrig {
namespace {

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
    const int width = window.max.x - window.min.x + 1;
    const int height = window.max.y - window.min.y + 1;
    cv::Mat image(height, width, CV_32FC3, cv::Scalar::all(0));
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
